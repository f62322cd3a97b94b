// Scalar transfer matrices (S, Q) as block-size-3 distributed PETSc matrices.
#include <algorithm>

#include "mlshell/level_hierarchy.hpp"

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
  PetscCall(MatXAIJSetPreallocation(*M, 3, dnnz.data(), onnz.data(), nullptr, nullptr));
  PetscCall(MatSetOption(*M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (int i = 0; i < owned; ++i) {
    const PetscInt row = rows.petsc_of(rows.local_points()[i]);
    for (SubdivisionMatrix::InnerIterator it(A, rows.local_points()[i]); it; ++it) {
      const PetscInt col = cols.petsc_of(static_cast<int>(it.col()));
      const double w = it.value();
      const PetscScalar block[9] = {w, 0, 0, 0, w, 0, 0, 0, w};
      PetscCall(MatSetValuesBlocked(*M, 1, &row, 1, &col, block, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
