// Element matrices straight into the CSR arrays (see element_matrix_assembly.hpp).
#include "mlshell/element_matrix_assembly.hpp"

#include <petsc/private/matimpl.h>    // Mat's ops: assembly begins with the ghost rows' exchange
#include <petsc/private/petscimpl.h>  // PetscObjectStateIncrease
#include <petscsf.h>

#include <algorithm>
#include <memory>

namespace mlshell {

namespace {

constexpr const char* kColumnsKey = "mlshell_block_columns";

/// The rows of ghost points (owned by other ranks) that this rank's elements add to: summed
/// here in 3 × 3 blocks and sent once per assembly, each block to its precomputed place in the
/// owner's CSR arrays (a PetscSF gather). PETSc's stash would send every entry with its indices,
/// sort and compress them on the sender and search each one's column on the receiver: at
/// 51,483 dofs on 2 ranks, 0.15 s a rank in a 2.1 s solve.
struct GhostRows {
  // This rank's side: ghost point l − num_owned has blocks [start[l], start[l + 1]).
  std::vector<PetscInt> start;
  std::vector<PetscInt> columns;    // each block's global block column, ascending in a row
  std::vector<PetscScalar> values;  // 9 per block, row-major; zero between assemblies
  // The owner's side: one slot per block another rank sends (the SF's multi-roots), with the
  // part (diagonal 0, off-diagonal 1), owned block row and block position in that row.
  std::vector<PetscInt> slot_part, slot_row, slot_block;
  std::vector<PetscScalar> received;  // 9 per slot
  PetscSF sf = nullptr;               // ghost block → its row's owned point on the owner
  MPI_Datatype block = MPI_DATATYPE_NULL;
  GhostRows() = default;
  GhostRows(const GhostRows&) = delete;
  GhostRows& operator=(const GhostRows&) = delete;
  ~GhostRows() {
    PetscSFDestroy(&sf);
    if (block != MPI_DATATYPE_NULL) MPI_Type_free(&block);
  }
};

/// What add_element_matrix needs besides the matrix: where each local point's block column is.
struct BlockColumns {
  Mat owner = nullptr;  // the matrix this was attached to (a duplicate has its own)
  PetscInt num_owned = 0;
  bool distributed = false;
  /// ≥ 0: block column of the diagonal part; ≤ −2: block −(c + 2) of the off-diagonal part's
  /// compressed columns; −1: the point couples with no owned row.
  std::vector<PetscInt> column_of_local;
  std::vector<PetscInt> block_of_local;  // global block index of each local point
  std::unique_ptr<GhostRows> ghosts;     // on more than one rank
};

PetscErrorCode destroy_columns(void* ctx) {
  delete static_cast<BlockColumns*>(ctx);
  return 0;
}

/// The BlockColumns attached to A, or null.
BlockColumns* block_columns_of(Mat A) {
  PetscContainer container = nullptr;
  if (PetscObjectQuery((PetscObject)A, kColumnsKey, (PetscObject*)&container) || !container)
    return nullptr;
  void* bc = nullptr;
  if (PetscContainerGetPointer(container, &bc)) return nullptr;
  auto* columns = static_cast<BlockColumns*>(bc);
  return columns->owner == A ? columns : nullptr;
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
/// `stride`: 3 in a CSR row of scalar columns (a block's first), 1 in a list of block columns.
template <int stride = 3>
inline PetscInt find_block(const PetscInt* row, PetscInt nb, PetscInt column) {
  if (nb == 0) return -1;
  PetscInt base = 0;
  for (PetscInt len = nb; len > 1;) {
    const PetscInt half = len / 2;
    base = row[stride * (base + half)] <= column ? base + half : base;
    len -= half;
  }
  return row[stride * base] == column ? base : -1;
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
                                const std::vector<std::vector<int>>& columns, PetscInt bs, Mat* A) {
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
                                             const std::vector<PetscInt>& block_of_local,
                                             const std::vector<std::vector<int>>& ghost_columns,
                                             Mat* A) {
  PetscFunctionBeginUser;
  PetscCall(create_prefilled(comm, first_owned, columns, 3, A));
  PetscCall(MatSetBlockSize(*A, 3));
  PetscCall(attach_block_columns(*A, block_of_local, ghost_columns));
  PetscFunctionReturn(0);
}

PetscErrorCode create_prefilled_point_matrix(MPI_Comm comm, PetscInt first_owned,
                                             const std::vector<std::vector<int>>& columns, Mat* A) {
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

namespace {

/// The block of owned row r (an owned point's index) in global block column c: its part
/// (0 diagonal, 1 off-diagonal) and position in the row, or part −1.
struct BlockPlace {
  int part = -1;
  PetscInt position = -1;
};

/// The CSR arrays of a matrix's parts (diagonal, off-diagonal), values writable.
struct PartArrays {
  Mat parts[2] = {nullptr, nullptr};
  const PetscInt* ia[2] = {nullptr, nullptr};
  const PetscInt* ja[2] = {nullptr, nullptr};
  PetscScalar* a[2] = {nullptr, nullptr};

  PetscErrorCode open(Mat A, bool distributed, bool values) {
    PetscFunctionBeginUser;
    PetscCall(parts_of(A, distributed, parts));
    for (int p = 0; p < 2; ++p)
      if (parts[p]) {
        PetscCall(MatSeqAIJGetCSRAndMemType(parts[p], &ia[p], &ja[p], nullptr, nullptr));
        if (values) PetscCall(MatSeqAIJGetArray(parts[p], &a[p]));
      }
    PetscFunctionReturn(0);
  }
  PetscErrorCode close() {
    PetscFunctionBeginUser;
    for (int p = 0; p < 2; ++p)
      if (parts[p] && a[p]) PetscCall(MatSeqAIJRestoreArray(parts[p], &a[p]));
    PetscFunctionReturn(0);
  }
  /// Adds the row-major 3 × 3 block `src` at block `position` of block row r of part p.
  void add(int p, PetscInt r, PetscInt position, const PetscScalar* src, PetscInt src_stride) {
    for (int c = 0; c < 3; ++c) {
      PetscScalar* dst = a[p] + ia[p][3 * r + c] + 3 * position;
      const PetscScalar* s = src + c * src_stride;
      dst[0] += s[0];
      dst[1] += s[1];
      dst[2] += s[2];
    }
  }
};

/// Sends the ghost rows' blocks to their owners, adds them there and zeroes them here
/// (collective).
PetscErrorCode exchange_ghost_rows(Mat A, BlockColumns& bc) {
  PetscFunctionBeginUser;
  GhostRows& g = *bc.ghosts;
  PetscCall(PetscSFGatherBegin(g.sf, g.block, g.values.data(), g.received.data()));
  PetscCall(PetscSFGatherEnd(g.sf, g.block, g.values.data(), g.received.data()));
  std::fill(g.values.begin(), g.values.end(), 0.0);
  PartArrays csr;
  PetscCall(csr.open(A, true, true));
  for (std::size_t s = 0; s < g.slot_row.size(); ++s)
    csr.add(static_cast<int>(g.slot_part[s]), g.slot_row[s], g.slot_block[s], &g.received[9 * s],
            3);
  PetscCall(csr.close());
  PetscFunctionReturn(0);
}

// The MPIAIJ methods that the matrices with ghost rows wrap (the same for every MPIAIJ matrix).
PetscErrorCode (*mpiaij_assembly_begin)(Mat, MatAssemblyType) = nullptr;
PetscErrorCode (*mpiaij_zero_entries)(Mat) = nullptr;

/// MatAssemblyBegin of a matrix with ghost rows: their exchange, then PETSc's own (whose stash
/// is then empty unless a block fell outside the ghost rows' pattern).
PetscErrorCode assembly_begin_with_ghost_rows(Mat A, MatAssemblyType type) {
  PetscFunctionBeginUser;
  if (BlockColumns* bc = block_columns_of(A); bc && bc->ghosts)
    PetscCall(exchange_ghost_rows(A, *bc));
  PetscCall(mpiaij_assembly_begin(A, type));
  PetscFunctionReturn(0);
}

/// MatZeroEntries of a matrix with ghost rows zeroes the blocks not yet sent too.
PetscErrorCode zero_entries_with_ghost_rows(Mat A) {
  PetscFunctionBeginUser;
  if (BlockColumns* bc = block_columns_of(A); bc && bc->ghosts)
    std::fill(bc->ghosts->values.begin(), bc->ghosts->values.end(), 0.0);
  PetscCall(mpiaij_zero_entries(A));
  PetscFunctionReturn(0);
}

/// The ghost rows of `ghost_columns` (BlockPattern::ghost_columns), their SF and, for the
/// blocks other ranks send here, their places in A (collective).
PetscErrorCode setup_ghost_rows(Mat A, const BlockColumns& bc,
                                const std::vector<std::vector<int>>& ghost_columns, GhostRows& g) {
  PetscFunctionBeginUser;
  MPI_Comm comm = PetscObjectComm((PetscObject)A);
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscInt* ranges;
  PetscCall(MatGetOwnershipRanges(A, &ranges));
  PetscInt rstart, rend;
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  const PetscInt first_owned = rstart / 3;
  // This rank's ghost blocks, each a leaf pointing at its row's point on the owner.
  g.start.assign(1, 0);
  std::vector<PetscSFNode> owners;
  for (std::size_t l = 0; l < ghost_columns.size(); ++l) {
    const PetscInt row = bc.block_of_local[bc.num_owned + l];
    const PetscInt owner =
        static_cast<PetscInt>(std::upper_bound(ranges, ranges + size + 1, 3 * row) - ranges - 1);
    for (int c : ghost_columns[l]) {
      g.columns.push_back(c);
      owners.push_back({static_cast<PetscInt>(owner), row - ranges[owner] / 3});
    }
    g.start.push_back(static_cast<PetscInt>(g.columns.size()));
  }
  PetscCall(PetscSFCreate(comm, &g.sf));
  PetscCall(PetscSFSetGraph(g.sf, bc.num_owned, static_cast<PetscInt>(owners.size()), nullptr,
                            PETSC_COPY_VALUES, owners.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(g.sf));
  // The owner learns each incoming block's column and finds its place once.
  const PetscInt* degree;
  PetscCall(PetscSFComputeDegreeBegin(g.sf, &degree));
  PetscCall(PetscSFComputeDegreeEnd(g.sf, &degree));
  PetscInt slots = 0;
  for (PetscInt r = 0; r < bc.num_owned; ++r) slots += degree[r];
  std::vector<PetscInt> incoming(slots);
  PetscCall(PetscSFGatherBegin(g.sf, MPIU_INT, g.columns.data(), incoming.data()));
  PetscCall(PetscSFGatherEnd(g.sf, MPIU_INT, g.columns.data(), incoming.data()));
  PartArrays csr;
  PetscCall(csr.open(A, true, false));
  const PetscInt* garray;
  PetscInt off_columns;
  PetscCall(MatMPIAIJGetSeqAIJ(A, nullptr, nullptr, &garray));
  PetscCall(MatGetSize(csr.parts[1], nullptr, &off_columns));
  g.slot_part.resize(slots), g.slot_row.resize(slots), g.slot_block.resize(slots);
  for (PetscInt r = 0, s = 0; r < bc.num_owned; ++r)
    for (PetscInt k = 0; k < degree[r]; ++k, ++s) {
      const PetscInt c = incoming[s];
      const bool diagonal = c >= first_owned && c < first_owned + bc.num_owned;
      const int p = diagonal ? 0 : 1;
      PetscInt column = 3 * (c - first_owned);  // the block's first scalar column in the part
      if (!diagonal) {
        const PetscInt* it = std::lower_bound(garray, garray + off_columns, 3 * c);
        column = it != garray + off_columns && *it == 3 * c ? it - garray : -1;
      }
      const PetscInt begin = csr.ia[p][3 * r];
      const PetscInt position =
          column < 0 ? -1
                     : find_block(csr.ja[p] + begin, (csr.ia[p][3 * r + 1] - begin) / 3, column);
      PetscCheck(position >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "another rank adds block (%" PetscInt_FMT ", %" PetscInt_FMT
                 ") outside the Hessian's pattern",
                 first_owned + r, c);
      g.slot_part[s] = p, g.slot_row[s] = r, g.slot_block[s] = position;
    }
  PetscCall(csr.close());
  g.values.assign(9 * g.columns.size(), 0.0);
  g.received.assign(9 * static_cast<std::size_t>(slots), 0.0);
  PetscCallMPI(MPI_Type_contiguous(9, MPIU_SCALAR, &g.block));
  PetscCallMPI(MPI_Type_commit(&g.block));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode attach_block_columns(Mat A, const std::vector<PetscInt>& block_of_local,
                                    const std::vector<std::vector<int>>& ghost_columns) {
  PetscFunctionBeginUser;
  PetscInt rstart, rend;
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  const PetscInt num_owned = (rend - rstart) / 3;
  PetscBool seq, mpi;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
  if (!seq && !mpi) PetscFunctionReturn(0);  // another type: MatSetValues does the work
  PetscCheck(ghost_columns.size() + num_owned == block_of_local.size(), PETSC_COMM_SELF,
             PETSC_ERR_ARG_SIZ, "attach_block_columns: %zu ghost rows for %zu ghost points",
             ghost_columns.size(), block_of_local.size() - static_cast<std::size_t>(num_owned));
  auto bc = std::make_unique<BlockColumns>();
  bc->owner = A;
  bc->num_owned = num_owned;
  bc->distributed = mpi;
  bc->block_of_local = block_of_local;
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
    bc->ghosts = std::make_unique<GhostRows>();
    PetscCall(setup_ghost_rows(A, *bc, ghost_columns, *bc->ghosts));
    if (A->ops->assemblybegin != assembly_begin_with_ghost_rows) {
      mpiaij_assembly_begin = A->ops->assemblybegin;
      mpiaij_zero_entries = A->ops->zeroentries;
      A->ops->assemblybegin = assembly_begin_with_ghost_rows;
      A->ops->zeroentries = zero_entries_with_ghost_rows;
    }
  }
  PetscContainer container;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)A), &container));
  PetscCall(PetscContainerSetPointer(container, bc.release()));
  PetscCall(PetscContainerSetUserDestroy(container, destroy_columns));
  PetscCall(PetscObjectCompose((PetscObject)A, kColumnsKey, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(0);
}

namespace {

/// Adds row block i of an element matrix (`rows`: its three rows, `width` apart), whose point is
/// a ghost, into the ghost rows; a block outside their pattern goes through PETSc's stash.
PetscErrorCode add_ghost_row(Mat A, BlockColumns& bc, PetscInt n, const PetscInt* nodes, PetscInt i,
                             const double* rows, PetscInt width) {
  PetscFunctionBeginUser;
  if (!bc.ghosts) {
    PetscCall(MatSetValuesBlockedLocal(A, 1, &nodes[i], n, nodes, rows, ADD_VALUES));
    PetscFunctionReturn(0);
  }
  GhostRows& g = *bc.ghosts;
  const PetscInt l = nodes[i] - bc.num_owned, begin = g.start[l], nb = g.start[l + 1] - begin;
  for (PetscInt j = 0; j < n; ++j) {
    const PetscInt k = find_block<1>(g.columns.data() + begin, nb, bc.block_of_local[nodes[j]]);
    if (k >= 0) {
      PetscScalar* dst = &g.values[9 * (begin + k)];
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) dst[3 * c + d] += rows[c * width + 3 * j + d];
      continue;
    }
    double block[9];
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) block[3 * c + d] = rows[c * width + 3 * j + d];
    PetscCall(MatSetValuesBlockedLocal(A, 1, &nodes[i], 1, &nodes[j], block, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode replace_matrix(Mat A, Mat* B) {
  PetscFunctionBeginUser;
  const PetscObjectState nonzero_state = A->nonzerostate;
  PetscCall(MatHeaderReplace(A, B));
  A->nonzerostate = std::max(nonzero_state, A->nonzerostate) + 1;
  PetscContainer container = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)A, kColumnsKey, (PetscObject*)&container));
  if (container) {  // the columns now belong to A
    void* bc = nullptr;
    PetscCall(PetscContainerGetPointer(container, &bc));
    static_cast<BlockColumns*>(bc)->owner = A;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode add_element_matrix(Mat A, PetscInt n, const PetscInt* nodes, const double* values) {
  PetscFunctionBeginUser;
  BlockColumns* bc = block_columns_of(A);
  if (!bc) {
    PetscCall(MatSetValuesBlockedLocal(A, n, nodes, n, nodes, values, ADD_VALUES));
    PetscFunctionReturn(0);
  }
  PartArrays csr;
  PetscCall(csr.open(A, bc->distributed, true));
  const PetscInt width = 3 * n;
  for (PetscInt i = 0; i < n; ++i) {
    const PetscInt r = nodes[i];
    const double* rows = values + 3 * i * width;
    if (r >= bc->num_owned) {  // another rank's row: its blocks go there at assembly
      PetscCall(add_ghost_row(A, *bc, n, nodes, i, rows, width));
      continue;
    }
    for (PetscInt j = 0; j < n; ++j) {
      const PetscInt col = bc->column_of_local[nodes[j]];
      const int p = col >= 0 ? 0 : 1;
      const PetscInt block = col >= 0 ? col : -col - 2;
      const PetscInt s = csr.ia[p] ? csr.ia[p][3 * r] : 0;
      const PetscInt k =
          col == -1 ? -1 : find_block(csr.ja[p] + s, (csr.ia[p][3 * r + 1] - s) / 3, 3 * block);
      PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "element block (%" PetscInt_FMT ", %" PetscInt_FMT
                 ") lies outside the Hessian's pattern",
                 r, nodes[j]);
      csr.add(p, r, k, rows + 3 * j, width);
    }
  }
  PetscCall(csr.close());
  PetscFunctionReturn(0);
}

}  // namespace mlshell
