// PC "vpatch" (vertex-patch additive Schwarz): the patches of a subdivision level (a control
// point's 3×3 block, ghosts included), M⁻¹ symmetric positive definite also for an indefinite
// operator, far fewer CG iterations than unpreconditioned CG on the trampoline's Hessian, and a
// clear error for a matrix without patches.
#include "mlshell/vertex_patch_pc.hpp"

#include <gtest/gtest.h>
#include <petscksp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "mlshell/multilevel_problem.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/subdivision/level_hierarchy.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "mlshell/vertex_patches.hpp"

using namespace mlshell;

namespace {

/// The trampoline's finest Hessian (refine 2, 1,083 dofs) at the start of its first step, on
/// the ranks of `comm`.
struct TrampolineHessian {
  std::unique_ptr<SubdivisionHierarchy> sub;
  std::unique_ptr<LevelHierarchy> levels;
  std::unique_ptr<MultilevelProblem> problem;
  Mat H = nullptr;
  Vec u = nullptr, v = nullptr;
  explicit TrampolineHessian(MPI_Comm comm = PETSC_COMM_SELF) {
    Scene s = parse_scene(std::filesystem::path(MLSHELL_SOURCE_DIR) / "examples/trampoline.yaml");
    s.geometry.refine = 2;
    sub = std::make_unique<SubdivisionHierarchy>(build_cage(s.geometry), 2);
    levels = std::make_unique<LevelHierarchy>(comm, *sub, 2, 3);
    problem = std::make_unique<MultilevelProblem>(s, *levels, CageFrame::from(s.geometry));
    levels->layout(0).create_vector(&u);
    VecDuplicate(u, &v);
    problem->synchronize(s.time.dt, u, v);
    problem->create_hessian(0, &H);
    problem->level(0).hessian(u, H);
  }
  ~TrampolineHessian() {
    MatDestroy(&H);
    VecDestroy(&u);
    VecDestroy(&v);
  }
};

/// The Hessian shifted by `shift` (a copy carries no patches: they are attached) and PC vpatch
/// set up on it; both destroyed with the object.
struct ShiftedPatchPc {
  Mat A = nullptr;
  PC pc = nullptr;
  PetscErrorCode setup = 0;
  ShiftedPatchPc(const TrampolineHessian& t, double shift, MPI_Comm comm) {
    MatDuplicate(t.H, MAT_COPY_VALUES, &A);
    setup = attach_vertex_patches(A, t.levels->layout(0).vertex_patches());
    MatShift(A, shift);
    PCCreate(comm, &pc);
    PCSetType(pc, "vpatch");
    PCSetOperators(pc, A, A);
    if (!setup) setup = PCSetUp(pc);
  }
  ~ShiftedPatchPc() {
    PCDestroy(&pc);
    MatDestroy(&A);
  }
};

/// A KSP on H with the given PC, rtol 1e-8; returns the iterations to converge.
PetscInt cg_iterations(Mat H, const char* pc_type, Vec b, Vec x) {
  KSP ksp;
  KSPCreate(PETSC_COMM_SELF, &ksp);
  KSPSetOperators(ksp, H, H);
  KSPSetType(ksp, KSPCG);
  KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 100000);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, pc_type);
  KSPSolve(ksp, b, x);
  PetscInt its;
  KSPGetIterationNumber(ksp, &its);
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp, &reason);
  EXPECT_GT(reason, 0) << pc_type;
  KSPDestroy(&ksp);
  return its;
}

Vec random_vector(Mat H, unsigned seed) {
  Vec x;
  MatCreateVecs(H, &x, nullptr);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  PetscInt n;
  VecGetLocalSize(x, &n);
  PetscScalar* a;
  VecGetArray(x, &a);
  for (PetscInt i = 0; i < n; ++i) a[i] = r(rng);
  VecRestoreArray(x, &a);
  return x;
}

/// M⁻¹ r from the PC against Σ_i R_iᵀ |A_i|⁻¹ R_i r formed densely, patch by patch, from the
/// whole matrix gathered on every rank (|A_i| by eigendecomposition, which is A_i for a positive
/// definite patch), for the Hessian and for one shifted to negative eigenvalues.
void expect_exact_patch_solves(MPI_Comm comm) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  TrampolineHessian t(comm);
  const VertexPatches* patches = nullptr;
  ASSERT_EQ(vertex_patches_of(t.H, &patches), 0);
  PetscInt n;
  MatGetSize(t.H, &n, nullptr);
  for (const double shift : {0.0, -1.0}) {
    const ShiftedPatchPc s(t, shift, comm);
    ASSERT_EQ(s.setup, 0);
    Mat A = s.A;
    PC pc = s.pc;
    Vec r = random_vector(A, 5), z;
    VecDuplicate(r, &z);
    PCApply(pc, r, z);
    // Everything on every rank: A, r and the PC's z.
    IS all;
    ISCreateStride(PETSC_COMM_SELF, n, 0, 1, &all);
    Mat* whole;
    MatCreateSubMatrices(A, 1, &all, &all, MAT_INITIAL_MATRIX, &whole);
    std::vector<double> r_all(n), z_all(n), z_ref(n, 0.0);
    for (auto [v, out] : {std::pair{r, &r_all}, std::pair{z, &z_all}}) {
      VecScatter to_all;
      Vec seq;
      VecScatterCreateToAll(v, &to_all, &seq);
      VecScatterBegin(to_all, v, seq, INSERT_VALUES, SCATTER_FORWARD);
      VecScatterEnd(to_all, v, seq, INSERT_VALUES, SCATTER_FORWARD);
      const PetscScalar* a;
      VecGetArrayRead(seq, &a);
      out->assign(a, a + n);
      VecRestoreArrayRead(seq, &a);
      VecScatterDestroy(&to_all);
      VecDestroy(&seq);
    }
    for (const auto& patch : patches->patches) {
      std::vector<PetscInt> idx;
      for (int q : patch)
        for (int c = 0; c < 3; ++c) idx.push_back(3 * patches->blocks[q] + c);
      const int m = static_cast<int>(idx.size());
      Eigen::MatrixXd Ai(m, m);  // MatGetValues is row-major; Ai is symmetric but for round-off
      MatGetValues(whole[0], m, idx.data(), m, idx.data(), Ai.data());
      Ai = (0.5 * (Ai + Ai.transpose())).eval();
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ai);
      Eigen::VectorXd lambda = es.eigenvalues().cwiseAbs();
      const double floor = 1e-12 * lambda.maxCoeff();
      for (int k = 0; k < m; ++k) lambda[k] = 1.0 / std::max(lambda[k], floor);
      Eigen::VectorXd ri(m);
      for (int k = 0; k < m; ++k) ri[k] = r_all[idx[k]];
      const Eigen::VectorXd zi =
          es.eigenvectors() * lambda.asDiagonal() * (es.eigenvectors().transpose() * ri);
      for (int k = 0; k < m; ++k) z_ref[idx[k]] += zi[k];
    }
    MPI_Allreduce(MPI_IN_PLACE, z_ref.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, comm);
    double diff = 0.0, norm = 0.0;
    for (PetscInt k = 0; k < n; ++k) {
      diff = std::max(diff, std::abs(z_all[k] - z_ref[k]));
      norm = std::max(norm, std::abs(z_ref[k]));
    }
    EXPECT_GT(norm, 0.0);
    EXPECT_LE(diff, 1e-9 * norm) << "shift " << shift << ": max |z - z_ref| " << diff
                                 << " against max |z_ref| " << norm;
    MatDestroySubMatrices(1, &whole);
    ISDestroy(&all);
    VecDestroy(&r);
    VecDestroy(&z);
  }
}

}  // namespace

TEST(VertexPatchPc, AppliesTheExactPatchSolves) { expect_exact_patch_solves(PETSC_COMM_SELF); }

// Two ranks: the patches of points next to the other rank's take rows of its matrix part.
TEST(MpiVertexPatchPc, AppliesTheExactPatchSolves) { expect_exact_patch_solves(PETSC_COMM_WORLD); }

// The patches are every corner of a point's faces however the elements are partitioned (the
// ghost-ring points at the partition's edge included), so M⁻¹ r on 2 ranks is M⁻¹ r on 1 rank
// for the same operator and r, in natural order, to round-off.
TEST(MpiVertexPatchPc, IsTheSameOperatorOnOneAndTwoRanks) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  TrampolineHessian distributed(PETSC_COMM_WORLD), serial(PETSC_COMM_SELF);
  const ParallelLayout &ld = distributed.levels->layout(0), &ls = serial.levels->layout(0);
  std::vector<double> r_natural;
  {
    Vec r = random_vector(serial.H, 11);
    ls.gather_natural(r, r_natural);  // one rank: all of it
    VecDestroy(&r);
  }
  std::vector<std::vector<double>> z_natural(2);
  for (int k = 0; k < 2; ++k) {
    TrampolineHessian& t = k == 0 ? serial : distributed;
    const ParallelLayout& layout = k == 0 ? ls : ld;
    const MPI_Comm comm = k == 0 ? PETSC_COMM_SELF : PETSC_COMM_WORLD;
    Vec r, z;
    layout.create_vector(&r);
    VecDuplicate(r, &z);
    layout.scatter_natural(k == 0 || rank == 0 ? r_natural : std::vector<double>{}, r);
    PC pc;
    PCCreate(comm, &pc);
    PCSetType(pc, "vpatch");
    PCSetOperators(pc, t.H, t.H);
    ASSERT_EQ(PCSetUp(pc), 0);
    PCApply(pc, r, z);
    layout.gather_natural(z, z_natural[k]);
    PCDestroy(&pc);
    VecDestroy(&r);
    VecDestroy(&z);
  }
  if (rank == 0) {
    ASSERT_EQ(z_natural[0].size(), z_natural[1].size());
    double diff = 0.0, norm = 0.0;
    for (size_t i = 0; i < z_natural[0].size(); ++i) {
      diff = std::max(diff, std::abs(z_natural[0][i] - z_natural[1][i]));
      norm = std::max(norm, std::abs(z_natural[0][i]));
    }
    EXPECT_GT(norm, 0.0);
    EXPECT_LE(diff, 1e-12 * norm) << "max |z_2 - z_1| " << diff << " against " << norm;
  }
}

/// PC vpatch reads rows of full 3 × 3 blocks one block at a time and other rows entry by
/// entry: the same operator stored both ways gives the same M⁻¹ r. A is the Hessian with some
/// entries set to zero, B the same matrix without those zeros in its pattern.
void expect_blocked_and_scalar_rows_agree(MPI_Comm comm) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  TrampolineHessian t(comm);
  Mat A, B;
  MatDuplicate(t.H, MAT_COPY_VALUES, &A);
  PetscInt first, last, N;
  MatGetOwnershipRange(A, &first, &last);
  MatGetSize(A, &N, nullptr);
  // Zeros inside the diagonal 3 × 3 blocks, which every pattern holds.
  for (PetscInt r = first; r < last; r += 5)
    if (r % 3 != 2) MatSetValue(A, r, r + 1, 0.0, INSERT_VALUES);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  MatCreate(comm, &B);
  MatSetSizes(B, last - first, last - first, N, N);
  MatSetType(B, MATAIJ);
  MatSetUp(B);
  MatSetOption(B, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE);
  int dropped = 0;
  for (PetscInt r = first; r < last; ++r) {
    PetscInt n;
    const PetscInt* cols;
    const PetscScalar* vals;
    MatGetRow(A, r, &n, &cols, &vals);
    for (PetscInt e = 0; e < n; ++e)
      if (vals[e] != 0.0)
        MatSetValue(B, r, cols[e], vals[e], INSERT_VALUES);
      else
        ++dropped;
    MatRestoreRow(A, r, &n, &cols, &vals);
  }
  MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY);
  EXPECT_GT(dropped, 0);
  const auto patches = t.levels->layout(0).vertex_patches();
  Vec r = random_vector(A, 7), za, zb;
  VecDuplicate(r, &za);
  VecDuplicate(r, &zb);
  for (auto [M, z] : {std::pair{A, za}, std::pair{B, zb}}) {
    ASSERT_EQ(attach_vertex_patches(M, patches), 0);
    PC pc;
    PCCreate(comm, &pc);
    PCSetType(pc, "vpatch");
    PCSetOperators(pc, M, M);
    ASSERT_EQ(PCSetUp(pc), 0);
    PCApply(pc, r, z);
    PCDestroy(&pc);
  }
  PetscReal norm, diff;
  VecNorm(za, NORM_INFINITY, &norm);
  VecAXPY(zb, -1.0, za);
  VecNorm(zb, NORM_INFINITY, &diff);
  EXPECT_GT(norm, 0.0);
  EXPECT_LE(diff, 1e-12 * norm) << "max |z_A - z_B| " << diff << " against " << norm;
  for (Vec* v : {&r, &za, &zb}) VecDestroy(v);
  MatDestroy(&A);
  MatDestroy(&B);
}

TEST(VertexPatchPc, ReadsBlockedAndScalarRowsAlike) {
  expect_blocked_and_scalar_rows_agree(PETSC_COMM_SELF);
}

TEST(MpiVertexPatchPc, ReadsBlockedAndScalarRowsAlike) {
  expect_blocked_and_scalar_rows_agree(PETSC_COMM_WORLD);
}

TEST(VertexPatches, ControlPointsTakeTheirThreeByThreeBlock) {
  TrampolineHessian t;
  const VertexPatches* patches = nullptr;
  ASSERT_EQ(vertex_patches_of(t.H, &patches), 0);
  ASSERT_NE(patches, nullptr);
  const ParallelLayout& layout = t.levels->layout(0);
  ASSERT_EQ(patches->patches.size(), static_cast<size_t>(layout.num_owned_points()));
  const auto& X = t.levels->discretization(0).points();
  const double h = 1.0 / 16.0;  // 4×4 cage refined twice
  for (int i = 0; i < layout.num_owned_points(); ++i) {
    const auto& patch = patches->patches[i];
    EXPECT_EQ(patch[0], i);
    const Point3& c = X[layout.local_points()[i]];
    // The patch is the control points within one cage edge in x and y (ghosts included), at
    // most nine of them.
    int expected = 0;
    for (int j = 0; j < layout.num_local_points(); ++j) {
      const Point3& q = X[layout.local_points()[j]];
      if (std::abs(q.x() - c.x()) < 1.01 * h && std::abs(q.y() - c.y()) < 1.01 * h) ++expected;
    }
    EXPECT_EQ(static_cast<int>(patch.size()), expected) << "point " << i;
    EXPECT_LE(patch.size(), 9u);
  }
}

TEST(VertexPatchPc, IsSymmetricPositiveDefiniteEvenForAnIndefiniteOperator) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  TrampolineHessian t;
  for (const double shift : {0.0, -1.0}) {  // the Hessian, and one with negative eigenvalues
    const ShiftedPatchPc s(t, shift, PETSC_COMM_SELF);
    ASSERT_EQ(s.setup, 0);
    Mat A = s.A;
    PC pc = s.pc;
    Vec x = random_vector(A, 1), y = random_vector(A, 2), Mx, My;
    VecDuplicate(x, &Mx);
    VecDuplicate(x, &My);
    PCApply(pc, x, Mx);
    PCApply(pc, y, My);
    PetscReal xMy, yMx, xMx, mx, my;
    VecDot(x, My, &xMy);
    VecDot(y, Mx, &yMx);
    VecDot(x, Mx, &xMx);
    VecNorm(Mx, NORM_2, &mx);
    VecNorm(My, NORM_2, &my);
    EXPECT_NEAR(xMy, yMx, 1e-12 * std::sqrt(mx * my) * 32.0) << "shift " << shift;
    EXPECT_GT(xMx, 0.0) << "shift " << shift;
    for (Vec* w : {&x, &y, &Mx, &My}) VecDestroy(w);
  }
}

// cond(H) ~ 3e7 (penalty β = h⁻⁵, small bending stiffness): plain CG needs thousands of
// iterations, vertex patches a few dozen.
TEST(VertexPatchPc, CutsTheIterationsOfConjugateGradientsOnTheTrampoline) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  TrampolineHessian t;
  Vec b = random_vector(t.H, 3), x;
  VecDuplicate(b, &x);
  const PetscInt plain = cg_iterations(t.H, PCNONE, b, x);
  const PetscInt patches = cg_iterations(t.H, "vpatch", b, x);
  std::printf("CG iterations to rtol 1e-8: %d plain, %d with vertex patches\n",
              static_cast<int>(plain), static_cast<int>(patches));
  EXPECT_LT(10 * patches, plain);
  VecDestroy(&b);
  VecDestroy(&x);
}

TEST(VertexPatchPc, NamesWhatItNeedsOnAMatrixWithoutPatches) {
  ASSERT_EQ(register_vertex_patch_pc(), 0);
  Mat A;
  MatCreateConstantDiagonal(PETSC_COMM_SELF, 3, 3, 3, 3, 2.0, &A);
  PC pc;
  PCCreate(PETSC_COMM_SELF, &pc);
  PCSetType(pc, "vpatch");
  PCSetOperators(pc, A, A);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode ierr = PCSetUp(pc);
  PetscPopErrorHandler();
  EXPECT_EQ(ierr, PETSC_ERR_ARG_WRONG);
  PCDestroy(&pc);
  MatDestroy(&A);
}
