// Scalar transfer matrices (S, Q) as block-size-3 distributed PETSc matrices.
#include <algorithm>

#include "mlshell/subdivision/level_hierarchy.hpp"

namespace mlshell {

PetscErrorCode create_block_transfer(const SubdivisionMatrix& A, const ParallelLayout& rows,
                                     const ParallelLayout& cols, Mat* M) {
  PetscFunctionBeginUser;
  const int owned = rows.num_owned_points();
  const int col_first = cols.first_owned(), col_last = col_first + cols.num_owned_points();
  std::vector<PetscInt> dnnz(owned, 0), onnz(owned, 0);
  for (int i = 0; i < owned; ++i)
    for (SubdivisionMatrix::InnerIterator it(A, rows.local_points()[i]); it; ++it) {
      const int c = cols.petsc_of(static_cast<int>(it.col()));
      (c >= col_first && c < col_last ? dnnz[i] : onnz[i])++;
    }
  PetscCall(MatCreate(rows.comm(), M));
  PetscCall(
      MatSetSizes(*M, 3 * owned, 3 * cols.num_owned_points(), PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*M, MATAIJ));
  PetscCall(MatSetBlockSize(*M, 3));
  // Each scalar weight w becomes the block w·I₃: only the three diagonal entries are stored.
  std::vector<PetscInt> d3(3 * owned), o3(3 * owned);
  for (int i = 0; i < 3 * owned; ++i) d3[i] = dnnz[i / 3], o3[i] = onnz[i / 3];
  PetscCall(MatSeqAIJSetPreallocation(*M, 0, d3.data()));
  PetscCall(MatMPIAIJSetPreallocation(*M, 0, d3.data(), 0, o3.data()));
  PetscCall(MatSetOption(*M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (int i = 0; i < owned; ++i) {
    const PetscInt row = rows.petsc_of(rows.local_points()[i]);
    for (SubdivisionMatrix::InnerIterator it(A, rows.local_points()[i]); it; ++it) {
      const PetscInt col = cols.petsc_of(static_cast<int>(it.col()));
      const PetscScalar w = it.value();
      for (PetscInt c = 0; c < 3; ++c) {
        const PetscInt r3 = 3 * row + c, c3 = 3 * col + c;
        PetscCall(MatSetValues(*M, 1, &r3, 1, &c3, &w, INSERT_VALUES));
      }
    }
  }
  PetscCall(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
