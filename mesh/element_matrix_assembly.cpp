// Element matrices straight into the CSR arrays (see element_matrix_assembly.hpp).
#include "mlshell/element_matrix_assembly.hpp"

#include <petsc/private/petscimpl.h>  // PetscObjectStateIncrease

#include <algorithm>
#include <memory>

namespace mlshell {

namespace {

constexpr const char* kColumnsKey = "mlshell_block_columns";

/// What add_element_matrix needs besides the matrix: where each local point's block column is.
struct BlockColumns {
  PetscInt num_owned = 0;
  bool distributed = false;
  /// ≥ 0: block column of the diagonal part; ≤ −2: block −(c + 2) of the off-diagonal part's
  /// compressed columns; −1: the point couples with no owned row.
  std::vector<PetscInt> column_of_local;
};

PetscErrorCode destroy_columns(void* ctx) {
  delete static_cast<BlockColumns*>(ctx);
  return 0;
}

/// The matrix's diagonal and off-diagonal SeqAIJ parts (the second null on one rank).
PetscErrorCode parts_of(Mat A, bool distributed, Mat parts[2]) {
  PetscFunctionBeginUser;
  if (distributed) {
    PetscCall(MatMPIAIJGetSeqAIJ(A, &parts[0], &parts[1], nullptr));
  } else {
    parts[0] = A;
    parts[1] = nullptr;
  }
  PetscFunctionReturn(0);
}

/// Checks that every owned block row of a part stores full 3 × 3 blocks: three scalar rows of
/// one length, columns in aligned triplets. add_element_matrix relies on it.
PetscErrorCode check_full_blocks(Mat part, PetscInt num_owned) {
  PetscFunctionBeginUser;
  const PetscInt *ia, *ja;
  PetscCall(MatSeqAIJGetCSRAndMemType(part, &ia, &ja, nullptr, nullptr));
  for (PetscInt r = 0; r < num_owned; ++r) {
    const PetscInt s = ia[3 * r], len = ia[3 * r + 1] - s;
    bool ok = len % 3 == 0 && ia[3 * r + 2] - ia[3 * r + 1] == len &&
              ia[3 * r + 3] - ia[3 * r + 2] == len;
    for (PetscInt c = 0; ok && c < 3; ++c)
      for (PetscInt k = 0; ok && k < len; ++k)
        ok = ja[ia[3 * r + c] + k] == ja[s + k] && ja[s + k] % 3 == k % 3;
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "block row %" PetscInt_FMT " of a Hessian does not store full 3 x 3 blocks", r);
  }
  PetscFunctionReturn(0);
}

/// Position k of the block whose first scalar column is `column` in a row of nb blocks, or −1.
/// Branch-free: the halving steps compile to conditional moves. A row holds about 25 blocks for
/// Catmull–Clark elements, and the branches of a plain binary search over them are taken at
/// random: mispredicted, they cost half of add_element_matrix's time (perf, 201,243 dofs).
inline PetscInt find_block(const PetscInt* row, PetscInt nb, PetscInt column) {
  if (nb == 0) return -1;
  PetscInt base = 0;
  for (PetscInt len = nb; len > 1;) {
    const PetscInt half = len / 2;
    base = row[3 * (base + half)] <= column ? base + half : base;
    len -= half;
  }
  return row[3 * base] == column ? base : -1;
}

}  // namespace

namespace {

/// CSR arrays of one SeqAIJ part, kept alive by the matrix that uses them.
struct CsrArrays {
  std::vector<PetscInt> i, j;
  std::vector<PetscScalar> a;
};

PetscErrorCode destroy_csr(void* ctx) {
  delete static_cast<CsrArrays*>(ctx);
  return 0;
}

/// Composes `arrays` on `part` (the matrix whose storage they are): freed with it.
PetscErrorCode give_arrays(Mat part, CsrArrays* arrays) {
  PetscFunctionBeginUser;
  PetscContainer container;
  PetscCall(PetscContainerCreate(PETSC_COMM_SELF, &container));
  PetscCall(PetscContainerSetPointer(container, arrays));
  PetscCall(PetscContainerSetUserDestroy(container, destroy_csr));
  PetscCall(PetscObjectCompose((PetscObject)part, "mlshell_csr_arrays", (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(0);
}

}  // namespace

namespace {

/// The prefilled matrix of `columns` with bs × bs blocks (bs = 3: a Hessian's pattern; bs = 1:
/// one scalar per block, the same pattern over points).
PetscErrorCode create_prefilled(MPI_Comm comm, PetscInt first_owned,
                                const std::vector<std::vector<int>>& columns, PetscInt bs,
                                Mat* A) {
  PetscFunctionBeginUser;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscInt num_owned = static_cast<PetscInt>(columns.size()), m = bs * num_owned;
  const auto owned = [&](PetscInt b) { return b >= first_owned && b < first_owned + num_owned; };
  // Scalar rows bs·i … bs·i + bs − 1 of block row i share its block columns, each expanded to
  // bs; the diagonal part numbers its columns from the first owned one, the other part globally.
  auto diag = std::make_unique<CsrArrays>(), off = std::make_unique<CsrArrays>();
  PetscInt nd = 0, no = 0;
  for (const auto& c : columns)
    for (int b : c) (owned(b) ? nd : no) += bs * bs;
  diag->i.reserve(m + 1), diag->j.reserve(nd), off->i.reserve(m + 1), off->j.reserve(no);
  diag->i.push_back(0), off->i.push_back(0);
  for (PetscInt r = 0; r < num_owned; ++r)
    for (PetscInt c = 0; c < bs; ++c) {
      for (int b : columns[r])
        for (PetscInt k = 0; k < bs; ++k) {
          if (owned(b))
            diag->j.push_back(bs * (b - first_owned) + k);
          else
            off->j.push_back(bs * static_cast<PetscInt>(b) + k);
        }
      diag->i.push_back(static_cast<PetscInt>(diag->j.size()));
      off->i.push_back(static_cast<PetscInt>(off->j.size()));
    }
  diag->a.assign(diag->j.size(), 0.0);
  off->a.assign(off->j.size(), 0.0);
  if (size == 1) {
    PetscCall(
        MatCreateSeqAIJWithArrays(comm, m, m, diag->i.data(), diag->j.data(), diag->a.data(), A));
    PetscCall(give_arrays(*A, diag.release()));
  } else {
    PetscCall(MatCreateMPIAIJWithSplitArrays(comm, m, m, PETSC_DETERMINE, PETSC_DETERMINE,
                                             diag->i.data(), diag->j.data(), diag->a.data(),
                                             off->i.data(), off->j.data(), off->a.data(), A));
    Mat parts[2];
    PetscCall(MatMPIAIJGetSeqAIJ(*A, &parts[0], &parts[1], nullptr));
    PetscCall(give_arrays(parts[0], diag.release()));
    PetscCall(give_arrays(parts[1], off.release()));
  }
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode create_prefilled_block_matrix(MPI_Comm comm, PetscInt first_owned,
                                             const std::vector<std::vector<int>>& columns,
                                             const std::vector<PetscInt>& block_of_local, Mat* A) {
  PetscFunctionBeginUser;
  PetscCall(create_prefilled(comm, first_owned, columns, 3, A));
  PetscCall(MatSetBlockSize(*A, 3));
  PetscCall(attach_block_columns(*A, block_of_local));
  PetscFunctionReturn(0);
}

PetscErrorCode create_prefilled_point_matrix(MPI_Comm comm, PetscInt first_owned,
                                             const std::vector<std::vector<int>>& columns,
                                             Mat* A) {
  return create_prefilled(comm, first_owned, columns, 1, A);
}

PetscErrorCode add_point_matrix(Mat A, Mat M) {
  PetscFunctionBeginUser;
  PetscBool mpi;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
  Mat a_parts[2], m_parts[2];
  PetscCall(parts_of(A, mpi, a_parts));
  PetscCall(parts_of(M, mpi, m_parts));
  for (int p = 0; p < 2; ++p) {
    if (!a_parts[p]) continue;
    const PetscInt *ia, *ja, *im, *jm;
    PetscCall(MatSeqAIJGetCSRAndMemType(a_parts[p], &ia, &ja, nullptr, nullptr));
    PetscCall(MatSeqAIJGetCSRAndMemType(m_parts[p], &im, &jm, nullptr, nullptr));
    PetscInt rows;
    PetscCall(MatGetLocalSize(m_parts[p], &rows, nullptr));
    // The same pattern: block k of A's block row r is entry k of M's row r, its first column
    // three times M's (the off-diagonal parts' compressed columns included).
    for (PetscInt r = 0; r < rows; ++r) {
      bool same = ia[3 * r + 1] - ia[3 * r] == 3 * (im[r + 1] - im[r]);
      for (PetscInt k = im[r]; same && k < im[r + 1]; ++k)
        same = ja[ia[3 * r] + 3 * (k - im[r])] == 3 * jm[k];
      PetscCheck(same, PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP,
                 "add_point_matrix: row %" PetscInt_FMT " of the Hessian has another pattern", r);
    }
    const PetscScalar* m;
    PetscScalar* a;
    PetscCall(MatSeqAIJGetArrayRead(m_parts[p], &m));
    PetscCall(MatSeqAIJGetArray(a_parts[p], &a));
    for (PetscInt r = 0; r < rows; ++r)
      for (PetscInt c = 0; c < 3; ++c) {
        PetscScalar* row = a + ia[3 * r + c] + c;  // the (c, c) entry of the row's first block
        for (PetscInt k = im[r]; k < im[r + 1]; ++k) row[3 * (k - im[r])] += m[k];
      }
    PetscCall(MatSeqAIJRestoreArray(a_parts[p], &a));
    PetscCall(MatSeqAIJRestoreArrayRead(m_parts[p], &m));
  }
  PetscCall(PetscObjectStateIncrease((PetscObject)A));
  PetscFunctionReturn(0);
}

PetscErrorCode attach_block_columns(Mat A, const std::vector<PetscInt>& block_of_local) {
  PetscFunctionBeginUser;
  PetscInt rstart, rend;
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  const PetscInt num_owned = (rend - rstart) / 3;
  PetscBool seq, mpi;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
  if (!seq && !mpi) PetscFunctionReturn(0);  // another type: MatSetValues does the work
  auto* bc = new BlockColumns;
  bc->num_owned = num_owned;
  bc->distributed = mpi;
  bc->column_of_local.assign(block_of_local.size(), -1);
  for (PetscInt l = 0; l < num_owned; ++l) bc->column_of_local[l] = l;
  Mat parts[2];
  PetscCall(parts_of(A, mpi, parts));
  for (Mat part : parts)
    if (part) PetscCall(check_full_blocks(part, num_owned));
  if (mpi) {
    const PetscInt* garray;
    PetscInt nb;
    PetscCall(MatMPIAIJGetSeqAIJ(A, nullptr, nullptr, &garray));
    PetscCall(MatGetSize(parts[1], nullptr, &nb));
    for (size_t l = num_owned; l < block_of_local.size(); ++l) {
      const PetscInt* it = std::lower_bound(garray, garray + nb, 3 * block_of_local[l]);
      if (it != garray + nb && *it == 3 * block_of_local[l])
        bc->column_of_local[l] = -((it - garray) / 3 + 2);
    }
  }
  PetscContainer container;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)A), &container));
  PetscCall(PetscContainerSetPointer(container, bc));
  PetscCall(PetscContainerSetUserDestroy(container, destroy_columns));
  PetscCall(PetscObjectCompose((PetscObject)A, kColumnsKey, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(0);
}

PetscErrorCode add_element_matrix(Mat A, PetscInt n, const PetscInt* nodes, const double* values) {
  PetscFunctionBeginUser;
  PetscContainer container = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)A, kColumnsKey, (PetscObject*)&container));
  if (!container) {
    PetscCall(MatSetValuesBlockedLocal(A, n, nodes, n, nodes, values, ADD_VALUES));
    PetscFunctionReturn(0);
  }
  const BlockColumns* bc;
  PetscCall(PetscContainerGetPointer(container, (void**)&bc));
  Mat parts[2];
  PetscCall(parts_of(A, bc->distributed, parts));
  const PetscInt *ia[2] = {nullptr, nullptr}, *ja[2] = {nullptr, nullptr};
  PetscScalar* a[2] = {nullptr, nullptr};
  for (int p = 0; p < 2; ++p)
    if (parts[p]) {
      PetscCall(MatSeqAIJGetCSRAndMemType(parts[p], &ia[p], &ja[p], nullptr, nullptr));
      PetscCall(MatSeqAIJGetArray(parts[p], &a[p]));
    }
  const PetscInt width = 3 * n;
  for (PetscInt i = 0; i < n; ++i) {
    const PetscInt r = nodes[i];
    const double* rows = values + 3 * i * width;
    if (r >= bc->num_owned) {  // another rank's row: through PETSc's stash
      PetscCall(MatSetValuesBlockedLocal(A, 1, &nodes[i], n, nodes, rows, ADD_VALUES));
      continue;
    }
    for (PetscInt j = 0; j < n; ++j) {
      const PetscInt col = bc->column_of_local[nodes[j]];
      const int p = col >= 0 ? 0 : 1;
      const PetscInt block = col >= 0 ? col : -col - 2;
      const PetscInt s = ia[p] ? ia[p][3 * r] : 0;
      const PetscInt k =
          col == -1 ? -1 : find_block(ja[p] + s, (ia[p][3 * r + 1] - s) / 3, 3 * block);
      PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "element block (%" PetscInt_FMT ", %" PetscInt_FMT
                 ") lies outside the Hessian's pattern",
                 r, nodes[j]);
      for (int c = 0; c < 3; ++c) {
        PetscScalar* dst = a[p] + ia[p][3 * r + c] + 3 * k;
        const double* src = rows + c * width + 3 * j;
        dst[0] += src[0];
        dst[1] += src[1];
        dst[2] += src[2];
      }
    }
  }
  for (int p = 0; p < 2; ++p)
    if (parts[p]) PetscCall(MatSeqAIJRestoreArray(parts[p], &a[p]));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
