// Element matrices written straight into the CSR arrays (element_matrix_assembly.hpp) give the
// matrix MatSetValuesBlockedLocal gives, on one rank and on two (rows of other ranks, sent as
// ghost-row blocks or, outside their pattern, through PETSc's stash; ghost columns), and a block
// outside the pattern is an error, not a silent drop.
#include "mlshell/element_matrix_assembly.hpp"

#include <gtest/gtest.h>

#include <random>

#include "mlshell/vertex_patches.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

/// Adds a random unsymmetric element matrix per local element into `direct` (the fast path)
/// and `reference` (MatSetValuesBlockedLocal); returns how many of them touch rows or columns
/// of points this rank does not own.
int add_random_elements(const TestProblem& tp, Mat direct, Mat reference) {
  int touching_ghosts = 0;
  for (int f : tp.layout->local_elements()) {
    const std::vector<int> stencil = tp.disc->stencil(f);
    const auto nodes = to_local_nodes(*tp.layout, stencil.data(), static_cast<int>(stencil.size()));
    const PetscInt n = static_cast<PetscInt>(nodes.size());
    std::mt19937 rng(f);  // the same values for an element on any number of ranks
    std::uniform_real_distribution<double> dist(-1.0, 1.0);
    std::vector<double> values(9 * n * n);
    for (double& v : values) v = dist(rng);
    PetscCallAbort(PETSC_COMM_SELF, add_element_matrix(direct, n, nodes.data(), values.data()));
    PetscCallAbort(PETSC_COMM_SELF,
                   MatSetValuesBlockedLocal(reference, n, nodes.data(), n, nodes.data(),
                                            values.data(), ADD_VALUES));
    for (PetscInt v : nodes)
      if (v >= tp.layout->num_owned_points()) {
        ++touching_ghosts;
        break;
      }
  }
  for (Mat A : {direct, reference}) {
    MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  }
  return touching_ghosts;
}

/// A matrix with the layout's sizes and local-to-global map and nothing else: no prefilled
/// pattern, PETSc's own communication in every assembly.
Mat plain_matrix(const TestProblem& tp) {
  Mat A;
  const PetscInt n = 3 * tp.layout->num_owned_points();
  MatCreateAIJ(tp.layout->comm(), n, n, PETSC_DETERMINE, PETSC_DETERMINE, 0, nullptr, 0, nullptr,
               &A);
  MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE);
  MatSetBlockSize(A, 3);
  ISLocalToGlobalMapping l2g;
  std::vector<PetscInt> blocks;
  for (int p : tp.layout->local_points()) blocks.push_back(tp.layout->petsc_of(p));
  ISLocalToGlobalMappingCreate(tp.layout->comm(), 3, static_cast<PetscInt>(blocks.size()),
                               blocks.data(), PETSC_COPY_VALUES, &l2g);
  MatSetLocalToGlobalMapping(A, l2g, l2g);
  ISLocalToGlobalMappingDestroy(&l2g);
  return A;
}

/// ‖direct − reference‖_F / ‖reference‖_F: `direct` made by the layout (prefilled, or a
/// duplicate of its first matrix, with its fixed off-process pattern) and summed into its CSR
/// arrays, `reference` a plain matrix summed by MatSetValuesBlockedLocal, both twice (the second
/// sum lands on the first: the arrays are added to, not overwritten; and the second assembly
/// reuses the first's communication).
/// With `without_ghost_pattern`, the ghost rows have no pattern of their own: every block of
/// another rank's row goes through PETSc's stash.
double relative_matrix_difference(const TestProblem& tp, int* touching_ghosts,
                                  bool without_ghost_pattern = false) {
  Mat direct, reference = plain_matrix(tp);
  tp.layout->create_matrix(&direct);
  if (without_ghost_pattern) {
    const auto& blocks = tp.layout->vertex_patches()->blocks;
    const std::vector<std::vector<int>> none(blocks.size() - tp.layout->num_owned_points());
    EXPECT_EQ(attach_block_columns(direct, blocks, none), 0);
  }
  for (int pass = 0; pass < 2; ++pass)
    *touching_ghosts = add_random_elements(tp, direct, reference);
  PetscReal norm, diff;
  MatNorm(reference, NORM_FROBENIUS, &norm);
  MatAXPY(reference, -1.0, direct, DIFFERENT_NONZERO_PATTERN);
  MatNorm(reference, NORM_FROBENIUS, &diff);
  MatDestroy(&direct);
  MatDestroy(&reference);
  return diff / norm;
}

}  // namespace

TEST(ElementMatrixAssembly, MatchesMatSetValuesOnOneRank) {
  TestProblem tp("all", PETSC_COMM_SELF);
  int touching_ghosts;
  EXPECT_LT(relative_matrix_difference(tp, &touching_ghosts), 1e-14);
}

TEST(ElementMatrixAssembly, LaterMatricesOfALayoutShareItsPatternNotItsValues) {
  // The first matrix is prefilled; later ones duplicate its structure (ParallelLayout::
  // create_matrix). A duplicate starts at zero, has the same nonzeros, takes the fast path and
  // keeps its values to itself.
  TestProblem tp("elastic_denim", PETSC_COMM_SELF);
  Mat first, second, reference;
  tp.layout->create_matrix(&first);
  tp.layout->create_matrix(&second);
  tp.layout->create_matrix(&reference);
  MatShift(first, 1.0);
  PetscReal norm;
  MatNorm(second, NORM_FROBENIUS, &norm);
  EXPECT_EQ(norm, 0.0);
  MatInfo a, b;
  MatGetInfo(first, MAT_LOCAL, &a);
  MatGetInfo(second, MAT_LOCAL, &b);
  EXPECT_EQ(a.nz_used, b.nz_used);
  EXPECT_GT(b.nz_used, 0.0);
  add_random_elements(tp, second, reference);
  MatAXPY(reference, -1.0, second, SAME_NONZERO_PATTERN);
  MatNorm(reference, NORM_FROBENIUS, &norm);
  EXPECT_EQ(norm, 0.0);
  MatShift(first, -1.0);  // the identity it was, if the second's values stayed apart
  MatNorm(first, NORM_FROBENIUS, &norm);
  EXPECT_EQ(norm, 0.0) << "the second matrix's values reached the first";
  for (Mat* m : {&first, &second, &reference}) MatDestroy(m);
}

TEST(ElementMatrixAssembly, BlockOutsideThePatternIsAnError) {
  TestProblem tp("elastic_denim", PETSC_COMM_SELF);
  Mat A;
  tp.layout->create_matrix(&A);
  // The first and last points of the 6 × 6-element rectangle share no element.
  const PetscInt nodes[2] = {0, tp.layout->num_local_points() - 1};
  const std::vector<double> values(36, 1.0);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode ierr = add_element_matrix(A, 2, nodes, values.data());
  PetscPopErrorHandler();
  EXPECT_EQ(ierr, PETSC_ERR_ARG_OUTOFRANGE);
  MatDestroy(&A);
}

/// On 2 ranks: the matrix is MatSetValuesBlockedLocal's, and some elements touch the other
/// rank's points (else the test checks nothing).
void expect_the_same_matrix_on_two_ranks(bool without_ghost_pattern) {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec -n 2";
  TestProblem tp("all", PETSC_COMM_WORLD);
  int touching_ghosts, total;
  const double difference = relative_matrix_difference(tp, &touching_ghosts, without_ghost_pattern);
  MPI_Allreduce(&touching_ghosts, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_GT(total, 0) << "no element touches another rank's points: the test checks nothing";
  EXPECT_LT(difference, 1e-14);
}

TEST(MpiElementMatrixAssembly, MatchesMatSetValuesWithRowsOfOtherRanks) {
  expect_the_same_matrix_on_two_ranks(false);
}

TEST(MpiElementMatrixAssembly, GhostRowBlocksOutsideTheirPatternGoThroughTheStash) {
  expect_the_same_matrix_on_two_ranks(true);
}
