// The distributed shell prolongation (triangle_transfer.hpp): one VecScatter gathers the coarse
// vertices of this rank's owned fine vertices' columns; the kernel runs per owned fine vertex;
// the transpose adds back with the reverse scatter.
#include "mlshell/prolongation/triangle_transfer.hpp"

#include <algorithm>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace mlshell {

namespace {

int global_points(const ParallelLayout& layout) {
  int owned = layout.num_owned_points(), total = 0;
  MPI_Allreduce(&owned, &total, 1, MPI_INT, MPI_SUM, layout.comm());
  return total;
}

/// Throws on every rank if `bad` holds on any.
void check_everywhere(MPI_Comm comm, bool bad, const std::string& message) {
  int local = bad ? 1 : 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any) throw std::invalid_argument("ShellTransfer: " + message);
}

}  // namespace

ShellTransfer::ShellTransfer(const ParallelLayout& coarse, const ParallelLayout& fine,
                             std::shared_ptr<const ShellProlongation> prolongation,
                             double relative_cost, std::vector<int> coarse_to_fine)
    : coarse_(coarse),
      fine_(fine),
      prolongation_(std::move(prolongation)),
      relative_cost_(relative_cost) {
  MPI_Comm comm = fine.comm();
  const int nc = global_points(coarse), nf = global_points(fine);
  check_everywhere(comm, !prolongation_, "no prolongation given");
  {
    std::ostringstream s;
    s << "the fine level has " << nf << " points but the prolongation " << prolongation_->num_fine()
      << " fine vertices";
    check_everywhere(comm, nf != prolongation_->num_fine(), s.str());
  }
  bool bad_column = false;
  for (int i = 0; i < prolongation_->num_fine(); ++i)
    for (int c : prolongation_->columns(i)) bad_column |= c < 0 || c >= nc;
  {
    std::ostringstream s;
    s << "the prolongation reads coarse vertices outside the coarse level's " << nc << " points";
    check_everywhere(comm, bad_column, s.str());
  }
  if (!coarse_to_fine.empty()) {
    std::ostringstream s;
    s << "coarse_to_fine has " << coarse_to_fine.size() << " entries for " << nc
      << " coarse points, or names a fine vertex outside 0.." << nf - 1;
    const bool bad = static_cast<int>(coarse_to_fine.size()) != nc ||
                     std::any_of(coarse_to_fine.begin(), coarse_to_fine.end(),
                                 [nf](int m) { return m < 0 || m >= nf; });
    check_everywhere(comm, bad, s.str());
  }

  // The coarse vertices this rank reads, sorted by natural index, and each column's slot.
  const int owned = fine.num_owned_points();
  fine_natural_.assign(fine.local_points().begin(), fine.local_points().begin() + owned);
  std::vector<int> needed;
  for (int i : fine_natural_)
    for (int c : prolongation_->columns(i)) needed.push_back(c);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  slots_.resize(owned);
  for (int j = 0; j < owned; ++j)
    for (int k = 0; k < 3; ++k)
      slots_[j][k] =
          static_cast<int>(std::lower_bound(needed.begin(), needed.end(),
                                            prolongation_->columns(fine_natural_[j])[k]) -
                           needed.begin());

  const int n = static_cast<int>(needed.size());
  std::vector<PetscInt> blocks(n);
  for (int s = 0; s < n; ++s) blocks[s] = coarse.petsc_of(needed[s]);
  Vec coarse_template, fine_template, rest;
  IS from;
  PetscCallAbort(comm, coarse.create_vector(&coarse_template));
  PetscCallAbort(comm, VecCreateSeq(PETSC_COMM_SELF, 3 * n, &gathered_));
  PetscCallAbort(comm,
                 ISCreateBlock(PETSC_COMM_SELF, 3, n, blocks.data(), PETSC_COPY_VALUES, &from));
  PetscCallAbort(comm, VecScatterCreate(coarse_template, from, gathered_, nullptr, &gather_));
  PetscCallAbort(comm, ISDestroy(&from));

  // X̄_c where it is read, and P(X̄_c) (= X̄_f to round-off) where this rank writes.
  PetscCallAbort(comm, coarse.create_coordinates(&rest));
  rest_gathered_.assign(n, Point3::Zero());
  PetscCallAbort(comm, gather(rest, false, rest_gathered_));
  PetscCallAbort(comm, VecDestroy(&rest));
  rest_image_.resize(owned);
  for (int j = 0; j < owned; ++j)
    rest_image_[j] =
        prolongation_->point(fine_natural_[j], rest_gathered_[slots_[j][0]],
                             rest_gathered_[slots_[j][1]], rest_gathered_[slots_[j][2]]);

  // Π: coarse vertex k (owned, PETSc order) reads fine vertex m(k).
  if (!coarse_to_fine.empty()) {
    const int owned_coarse = coarse.num_owned_points();
    std::vector<PetscInt> source(owned_coarse), target(owned_coarse);
    for (int j = 0; j < owned_coarse; ++j) {
      source[j] = fine.petsc_of(coarse_to_fine[coarse.local_points()[j]]);
      target[j] = coarse.first_owned() + j;
    }
    IS is_source, is_target;
    PetscCallAbort(comm, fine.create_vector(&fine_template));
    PetscCallAbort(comm, ISCreateBlock(PETSC_COMM_SELF, 3, owned_coarse, source.data(),
                                       PETSC_COPY_VALUES, &is_source));
    PetscCallAbort(comm, ISCreateBlock(PETSC_COMM_SELF, 3, owned_coarse, target.data(),
                                       PETSC_COPY_VALUES, &is_target));
    PetscCallAbort(
        comm, VecScatterCreate(fine_template, is_source, coarse_template, is_target, &survivors_));
    PetscCallAbort(comm, ISDestroy(&is_source));
    PetscCallAbort(comm, ISDestroy(&is_target));
    PetscCallAbort(comm, VecDestroy(&fine_template));
  }
  PetscCallAbort(comm, VecDestroy(&coarse_template));
}

ShellTransfer::~ShellTransfer() {
  VecScatterDestroy(&gather_);
  VecScatterDestroy(&survivors_);
  VecDestroy(&gathered_);
  MatDestroy(&J_);
}

PetscErrorCode ShellTransfer::gather(Vec u, bool with_rest, std::vector<Point3>& values) const {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(gather_, u, gathered_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(gather_, u, gathered_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a;
  PetscCall(VecGetArrayRead(gathered_, &a));
  values.resize(rest_gathered_.size());
  for (size_t s = 0; s < values.size(); ++s) {
    values[s] = Point3(a[3 * s], a[3 * s + 1], a[3 * s + 2]);
    if (with_rest) values[s] += rest_gathered_[s];
  }
  PetscCall(VecRestoreArrayRead(gathered_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::prolong(Vec coarse, Vec fine) const {
  PetscFunctionBeginUser;
  std::vector<Point3> x;
  PetscCall(gather(coarse, true, x));
  PetscScalar* out;
  PetscCall(VecGetArray(fine, &out));
  for (size_t j = 0; j < slots_.size(); ++j) {
    const auto& s = slots_[j];
    const Point3 p =
        prolongation_->point(fine_natural_[j], x[s[0]], x[s[1]], x[s[2]]) - rest_image_[j];
    for (int c = 0; c < 3; ++c) out[3 * j + c] = p[c];
  }
  PetscCall(VecRestoreArray(fine, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::prolong_correction(Vec x0, Vec x, Vec fine_correction) const {
  PetscFunctionBeginUser;
  std::vector<Point3> start, end;
  PetscCall(gather(x0, true, start));
  PetscCall(gather(x, true, end));
  PetscScalar* out;
  PetscCall(VecGetArray(fine_correction, &out));
  for (size_t j = 0; j < slots_.size(); ++j) {
    const auto& s = slots_[j];
    const int i = fine_natural_[j];
    const Point3 p = prolongation_->point(i, end[s[0]], end[s[1]], end[s[2]]) -
                     prolongation_->point(i, start[s[0]], start[s[1]], start[s[2]]);
    for (int c = 0; c < 3; ++c) out[3 * j + c] = p[c];
  }
  PetscCall(VecRestoreArray(fine_correction, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::update_jacobians(Vec x0) const {
  PetscFunctionBeginUser;
  std::vector<Point3> x;
  if (x0) {
    PetscCall(gather(x0, true, x));
  } else {  // the rest state (Levels::composite_norm): the blocks once, then kept
    if (rest_jacobians_.size() == slots_.size() && !slots_.empty()) {
      jacobians_ = rest_jacobians_;
      PetscFunctionReturn(0);
    }
    x = rest_gathered_;
  }
  jacobians_.resize(slots_.size());
  for (size_t j = 0; j < slots_.size(); ++j) {
    const auto& s = slots_[j];
    jacobians_[j] = prolongation_->jacobian(fine_natural_[j], x[s[0]], x[s[1]], x[s[2]]);
  }
  if (!x0) rest_jacobians_ = jacobians_;
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::prolong_direction(Vec x0, Vec direction, Vec fine) const {
  PetscFunctionBeginUser;
  PetscCall(update_jacobians(x0));
  std::vector<Point3> d;
  PetscCall(gather(direction, false, d));
  PetscScalar* out;
  PetscCall(VecGetArray(fine, &out));
  for (size_t j = 0; j < slots_.size(); ++j) {
    const auto& s = slots_[j];
    Eigen::Matrix<double, 9, 1> dj;
    dj << d[s[0]], d[s[1]], d[s[2]];
    const Eigen::Vector3d p = jacobians_[j] * dj;
    for (int c = 0; c < 3; ++c) out[3 * j + c] = p[c];
  }
  PetscCall(VecRestoreArray(fine, &out));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::restrict_gradient(Vec x0, Vec fine_gradient,
                                                Vec coarse_gradient) const {
  PetscFunctionBeginUser;
  PetscCall(update_jacobians(x0));
  PetscCall(restrict_blocks(
      fine_gradient, coarse_gradient,
      [&](size_t j, const Eigen::Vector3d& g) -> Eigen::Matrix<double, 9, 1> {
        return jacobians_[j].transpose() * g;
      }));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::restrict_intrinsic(Vec fine_gradient, Vec coarse_gradient) const {
  PetscFunctionBeginUser;
  PetscCall(restrict_blocks(
      fine_gradient, coarse_gradient,
      [&](size_t j, const Eigen::Vector3d& g) -> Eigen::Matrix<double, 9, 1> {
        const Eigen::Vector3d& w = prolongation_->embedding(fine_natural_[j]).weights;
        Eigen::Matrix<double, 9, 1> r;
        for (int k = 0; k < 3; ++k) r.segment<3>(3 * k) = w[k] * g;
        return r;
      }));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::restrict_blocks(
    Vec fine_gradient, Vec coarse_gradient,
    const std::function<Eigen::Matrix<double, 9, 1>(size_t, const Eigen::Vector3d&)>& block)
    const {
  PetscFunctionBeginUser;
  const PetscScalar* g;
  PetscScalar* a;
  PetscCall(VecGetArrayRead(fine_gradient, &g));
  PetscCall(VecZeroEntries(gathered_));
  PetscCall(VecGetArray(gathered_, &a));
  for (size_t j = 0; j < slots_.size(); ++j) {
    const Eigen::Matrix<double, 9, 1> r =
        block(j, Eigen::Vector3d(g[3 * j], g[3 * j + 1], g[3 * j + 2]));
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) a[3 * slots_[j][k] + c] += r[3 * k + c];
  }
  PetscCall(VecRestoreArray(gathered_, &a));
  PetscCall(VecRestoreArrayRead(fine_gradient, &g));
  PetscCall(VecZeroEntries(coarse_gradient));
  PetscCall(VecScatterBegin(gather_, gathered_, coarse_gradient, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(gather_, gathered_, coarse_gradient, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::jacobian_matrix(Vec x0, Mat* J) const {
  PetscFunctionBeginUser;
  PetscCall(update_jacobians(x0));
  const int owned = static_cast<int>(slots_.size());
  auto column_blocks = [&](int j) {
    std::array<PetscInt, 3> b;
    for (int k = 0; k < 3; ++k)
      b[k] = coarse_.petsc_of(prolongation_->columns(fine_natural_[j])[k]);
    return b;
  };
  if (!J_) {  // the pattern: three coarse blocks per fine block row
    const int first = coarse_.first_owned(), last = first + coarse_.num_owned_points();
    std::vector<PetscInt> diagonal(3 * owned), off(3 * owned);
    for (int j = 0; j < owned; ++j) {
      int on = 0;
      for (PetscInt b : column_blocks(j)) on += b >= first && b < last;
      for (int c = 0; c < 3; ++c) {
        diagonal[3 * j + c] = 3 * on;
        off[3 * j + c] = 3 * (3 - on);
      }
    }
    PetscCall(MatCreate(fine_.comm(), &J_));
    PetscCall(MatSetSizes(J_, 3 * owned, 3 * coarse_.num_owned_points(), PETSC_DETERMINE,
                          PETSC_DETERMINE));
    PetscCall(MatSetType(J_, MATAIJ));
    PetscCall(MatSetBlockSizes(J_, 3, 3));
    PetscCall(MatSeqAIJSetPreallocation(J_, 0, diagonal.data()));
    PetscCall(MatMPIAIJSetPreallocation(J_, 0, diagonal.data(), 0, off.data()));
    PetscCall(MatSetOption(J_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  }
  const PetscInt first_row = 3 * fine_.first_owned();
  for (int j = 0; j < owned; ++j) {
    PetscInt rows[3], cols[9];
    const auto b = column_blocks(j);
    for (int c = 0; c < 3; ++c) rows[c] = first_row + 3 * j + c;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) cols[3 * k + c] = 3 * b[k] + c;
    const Eigen::Matrix<double, 3, 9, Eigen::RowMajor> values = jacobians_[j];
    PetscCall(MatSetValues(J_, 3, rows, 9, cols, values.data(), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(J_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  *J = J_;
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::coarse_operator(Vec x0, Mat fine, MatReuse reuse, Mat* coarse) const {
  PetscFunctionBeginUser;
  Mat J;
  PetscCall(jacobian_matrix(x0, &J));
  PetscCall(MatPtAP(fine, J, reuse, PETSC_DEFAULT, coarse));
  PetscFunctionReturn(0);
}

PetscErrorCode ShellTransfer::project(Vec fine, Vec coarse, Projection kind) const {
  PetscFunctionBeginUser;
  MPI_Comm comm = fine_.comm();
  PetscCheck(kind == Projection::kNatural, comm, PETSC_ERR_SUP,
             "the shell prolongation offers only the natural projection (a survivor's "
             "displacement); least-squares and scaled-restriction projections need a linear "
             "transfer");
  PetscCheck(survivors_, comm, PETSC_ERR_SUP,
             "this shell transfer was built without coarse_to_fine: no natural projection");
  PetscCall(VecScatterBegin(survivors_, fine, coarse, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(survivors_, fine, coarse, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
