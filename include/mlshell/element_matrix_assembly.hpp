// Adding dense element matrices into the Hessians ParallelLayout::create_matrix makes, straight
// into their CSR arrays.
//
// PETSc's MatSetValuesBlockedLocal maps every block index to a global one, expands it into
// scalar indices and searches each value's column in its row: for a Catmull–Clark element
// (16 control points, 2,304 values) that cost more than computing the element (assembly
// benchmark: 57 % of energy + gradient + Hessian). The pattern of these matrices is fixed when
// they are made (every element block is prefilled with zeros and assembled once), so a block's
// position can be found once per block instead of once per value: block columns are local
// point indices, owned points are the diagonal part's block columns and ghost points a block of
// the off-diagonal part's compressed columns (`column_of_local`). Rows of ghost points (owned by
// other ranks) are summed here in blocks of their own fixed pattern (BlockPattern::
// ghost_columns) and sent at MatAssemblyBegin, each block to its place in the owner's CSR arrays
// found once (a PetscSF gather), instead of entry by entry through PETSc's stash.
//
// This plays the part of PETSc's COO assembly (MatSetPreallocationCOO / MatSetValuesCOO)
// without its per-entry index arrays: element entries outnumber the matrix's nonzeros about
// five to one for 16-point Catmull–Clark elements (37.7 M against 7.6 M at 51,483 dofs), where
// this holds one integer per local point.
#pragma once

#include <petscmat.h>

#include <vector>

namespace mlshell {

/// A new block-size-3 MATAIJ matrix on `comm` holding zeros on the given pattern (for each
/// owned block row, its sorted global block columns; the owned block rows are first_owned,
/// first_owned + 1, …), assembled, with what add_element_matrix needs attached.
/// `block_of_local` is the PETSc block index of each local point, owned ones first. The CSR
/// arrays are built here and handed to PETSc whole (MatCreateSeqAIJWithArrays,
/// MatCreateMPIAIJWithSplitArrays) instead of inserting the zeros row by row with MatSetValues
/// (the whole set-up at 51,483 dofs on 1 rank: 0.52 → 0.47 s). The matrix's sequential parts own
/// the arrays (composed containers, freed with them; PETSc 3.18 copies them on MatDuplicate).
/// `ghost_columns`: for each ghost point (local index − owned points), the sorted global block
/// columns this rank adds to its row (on one rank: none).
PetscErrorCode create_prefilled_block_matrix(MPI_Comm comm, PetscInt first_owned,
                                             const std::vector<std::vector<int>>& columns,
                                             const std::vector<PetscInt>& block_of_local,
                                             const std::vector<std::vector<int>>& ghost_columns,
                                             Mat* A);

/// The same pattern over points: a scalar MATAIJ matrix (block size 1) with one entry for each
/// block of create_prefilled_block_matrix's, prefilled with zeros and assembled, for operators
/// that act alike on x, y and z (the mass matrix M, whose Hessian block is M ⊗ I₃: a ninth of
/// the storage).
PetscErrorCode create_prefilled_point_matrix(MPI_Comm comm, PetscInt first_owned,
                                             const std::vector<std::vector<int>>& columns, Mat* A);

/// A += M ⊗ I₃: M a point matrix of A's pattern (create_prefilled_point_matrix), A a prefilled
/// block matrix or a duplicate of one, assembled. Straight into the CSR arrays: each entry of M
/// goes to the three diagonal entries of A's block in the same position.
PetscErrorCode add_point_matrix(Mat A, Mat M);

/// What create_prefilled_block_matrix attaches, for a matrix that has that pattern already (a
/// duplicate of a prefilled one: MatDuplicate does not carry it over). Collective. On more than
/// one rank it replaces the matrix's MatAssemblyBegin and MatZeroEntries by ones that also send
/// (and zero) the ghost rows' blocks, so the matrix assembles like any other.
PetscErrorCode attach_block_columns(Mat A, const std::vector<PetscInt>& block_of_local,
                                    const std::vector<std::vector<int>>& ghost_columns);

/// Gives A the structure and values of *B (made by create_prefilled_block_matrix, e.g. with a
/// larger pattern) under A's handle, so that solvers and preconditioners holding A see the new
/// pattern (MatHeaderReplace); *B is consumed. A's nonzero state grows, so a preconditioner
/// set up on A starts over (a new symbolic factorisation).
PetscErrorCode replace_matrix(Mat A, Mat* B);

/// A += the dense 3n × 3n row-major element matrix on local block indices `nodes`. Uses the
/// CSR arrays (and the ghost rows) when `A` was made by create_prefilled_block_matrix, else
/// MatSetValuesBlockedLocal. The caller assembles A afterwards (MAT_FINAL_ASSEMBLY) as with
/// MatSetValues.
PetscErrorCode add_element_matrix(Mat A, PetscInt n, const PetscInt* nodes, const double* values);

}  // namespace mlshell
