// Least-squares projection between subdivision levels (paper eq. 5.17–5.18).
#include <Eigen/SparseCholesky>

#include "mlshell/subdivision/subdivision_hierarchy.hpp"

namespace mlshell {

struct LeastSquaresProjection::Factor {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

LeastSquaresProjection::LeastSquaresProjection(const SubdivisionMatrix& S)
    : S_(S), factor_(std::make_unique<Factor>()) {
  const Eigen::SparseMatrix<double> StS = S.transpose() * S;
  factor_->ldlt.compute(StS);
  if (factor_->ldlt.info() != Eigen::Success)
    throw MeshError("least-squares projection: SᵀS is singular (S does not have full rank)");
}

LeastSquaresProjection::~LeastSquaresProjection() = default;

Eigen::MatrixXd LeastSquaresProjection::apply(const Eigen::MatrixXd& fine) const {
  return factor_->ldlt.solve(S_.transpose() * fine);
}

}  // namespace mlshell
