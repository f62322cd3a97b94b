// Distributed transfer operators between subdivision levels: S reproduces the refined control
// points, R = Sᵀ, Q S = I as PETSc matrices, and the composite norm (4.9).
#include <gtest/gtest.h>

#include <random>

#include "level_hierarchy_fixtures.hpp"

using namespace mlshell;

TEST(LevelHierarchy, ProlongationReproducesTheRefinedControlPoints) {
  HierarchyFixture fx(PETSC_COMM_SELF, 0);
  for (int l = 0; l < fx.levels->finest(); ++l) {
    const auto& X = fx.levels->discretization(l).mesh().points;
    const auto& Y = fx.levels->discretization(l + 1).mesh().points;
    std::vector<double> coarse, fine;
    for (const Point3& p : X) coarse.insert(coarse.end(), {p.x(), p.y(), p.z()});
    const std::vector<double> out = fx.apply(fx.levels->prolongation(l), l, l + 1, coarse);
    double worst = 0;
    for (size_t i = 0; i < Y.size(); ++i)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(out[3 * i + c] - Y[i][c]));
    EXPECT_LT(worst, 1e-14) << "level " << l;
  }
}

TEST(LevelHierarchy, ReverseSubdivisionInvertsProlongationAndRestrictionIsTheTranspose) {
  HierarchyFixture fx(PETSC_COMM_SELF, 0);
  for (int l = 0; l < fx.levels->finest(); ++l) {
    Mat QS;
    MatMatMult(fx.levels->projection(l), fx.levels->prolongation(l), MAT_INITIAL_MATRIX,
               PETSC_DEFAULT, &QS);
    MatShift(QS, -1.0);
    PetscReal err;
    MatNorm(QS, NORM_INFINITY, &err);
    EXPECT_LT(err, 1e-13) << "level " << l;
    MatDestroy(&QS);
    // (R x, y) = (x, S y)
    const auto x = fx.random(l + 1, 1), y = fx.random(l, 2);
    const auto Rx = fx.apply(fx.levels->restriction(l), l + 1, l, x);
    const auto Sy = fx.apply(fx.levels->prolongation(l), l, l + 1, y);
    double a = 0, b = 0;
    for (size_t i = 0; i < y.size(); ++i) a += Rx[i] * y[i];
    for (size_t i = 0; i < x.size(); ++i) b += x[i] * Sy[i];
    EXPECT_NEAR(a, b, 1e-12 * std::abs(b));
  }
}

TEST(LevelHierarchy, CompositeNormProlongatesToTheFinestLevel) {
  HierarchyFixture fx(PETSC_COMM_SELF, 0);
  const auto x = fx.random(0, 3);
  // Reference: the scalar subdivision matrices applied one after the other.
  Eigen::MatrixXd v(x.size() / 3, 3);
  for (int i = 0; i < v.rows(); ++i) v.row(i) << x[3 * i], x[3 * i + 1], x[3 * i + 2];
  for (int l = 0; l < fx.levels->finest(); ++l) v = fx.subdivision.subdivision(l) * v;
  Vec xv;
  fx.levels->layout(0).create_vector(&xv);
  fx.levels->layout(0).scatter_natural(x, xv);
  PetscReal norm;
  fx.levels->composite_norm(0, xv, &norm);
  EXPECT_NEAR(norm, v.norm(), 1e-13 * v.norm());
  VecDestroy(&xv);
}

TEST(LevelHierarchy, LeastSquaresProjectionSolvesTheNormalEquations) {
  HierarchyFixture fx(PETSC_COMM_SELF, 0);
  for (int l = 0; l < fx.levels->finest(); ++l) {
    const auto y = fx.random(l + 1, 7);
    Vec fine, coarse, back, normal;
    fx.levels->layout(l + 1).create_vector(&fine);
    fx.levels->layout(l).create_vector(&coarse);
    fx.levels->layout(l).create_vector(&normal);
    fx.levels->layout(l + 1).scatter_natural(y, fine);
    fx.levels->least_squares_projection(l, fine, coarse);
    // Sᵀ(S q − y) = 0
    VecDuplicate(fine, &back);
    MatMult(fx.levels->prolongation(l), coarse, back);
    VecAXPY(back, -1.0, fine);
    MatMult(fx.levels->restriction(l), back, normal);
    PetscReal r, ynorm;
    VecNorm(normal, NORM_INFINITY, &r);
    VecNorm(fine, NORM_INFINITY, &ynorm);
    EXPECT_LT(r, 1e-10 * ynorm) << "level " << l;
    for (Vec* v : {&fine, &coarse, &back, &normal}) VecDestroy(v);
  }
}
