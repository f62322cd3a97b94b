// Levels with inherited partitions and their transfer operators (see level_hierarchy.hpp).
#include "mlshell/subdivision/level_hierarchy.hpp"

#include <map>
#include <stdexcept>

#include "mlshell/log_events.hpp"

namespace mlshell {

namespace {

/// Owner of each coarse face: the most frequent owner among its interior children (ties: the
/// lowest rank). Ghost faces keep rank 0; only interior faces are elements.
std::vector<int> inherit_owners(const QuadMesh& coarse, const QuadMesh& fine,
                                const std::vector<int>& parent,
                                const std::vector<int>& fine_owner) {
  std::vector<std::map<int, int>> votes(coarse.num_faces());
  for (int f = 0; f < fine.num_faces(); ++f)
    if (!fine.is_ghost(f)) ++votes[parent[f]][fine_owner[f]];
  std::vector<int> owner(coarse.num_faces(), 0);
  for (int f = 0; f < coarse.num_faces(); ++f) {
    int best = -1;
    for (const auto& [rank, count] : votes[f])
      if (best < 0 || count > votes[f].at(best)) best = rank;
    if (best >= 0) owner[f] = best;
  }
  return owner;
}

}  // namespace

LevelHierarchy::LevelHierarchy(MPI_Comm comm, const SubdivisionHierarchy& sub, int coarsest,
                               int gauss) {
  const int top = sub.num_levels() - 1;
  if (coarsest < 0 || coarsest > top)
    throw std::invalid_argument("LevelHierarchy: bad coarsest level");
  levels_.resize(top - coarsest + 1);
  // Finest first: METIS there, inherited owners below.
  for (int l = top; l >= coarsest; --l) {
    Level& level = levels_[l - coarsest];
    {
      const LogEventScope event("Setup:basis");
      level.disc = std::make_unique<SubdivisionDiscretization>(sub.level(l), gauss);
    }
    const LogEventScope event("Setup:layout");
    if (l == top) {
      level.layout = std::make_unique<ParallelLayout>(comm, *level.disc);
    } else {
      const Level& finer = levels_[l - coarsest + 1];
      level.layout = std::make_unique<ParallelLayout>(
          comm, *level.disc,
          inherit_owners(sub.level(l), sub.level(l + 1), sub.parent_faces(l),
                         finer.layout->face_owners()));
    }
  }
  const LogEventScope event("Setup:transfers");
  transfers_.resize(levels_.size() - 1);
  for (int l = 0; l + 1 < num_levels(); ++l) {
    Transfer& t = transfers_[l];
    PetscCallAbort(
        comm, create_block_transfer(sub.subdivision(coarsest + l), layout(l + 1), layout(l), &t.S));
    PetscCallAbort(comm, MatTranspose(t.S, MAT_INITIAL_MATRIX, &t.R));
    PetscCallAbort(comm, create_block_transfer(sub.reverse_subdivision(coarsest + l), layout(l),
                                               layout(l + 1), &t.Q));
    // Catmull–Clark refinement quadruples the faces: a coarse evaluation costs a quarter.
    t.linear = std::make_unique<LinearTransfer>(
        t.S, t.R, t.Q, 0.25,
        [this, l](Vec fine, Vec coarse) { return least_squares_projection(l, fine, coarse); });
  }
}

LevelHierarchy::~LevelHierarchy() {
  for (Transfer& t : transfers_) {
    t.linear.reset();
    MatDestroy(&t.S);
    MatDestroy(&t.R);
    MatDestroy(&t.Q);
    MatDestroy(&t.StS);
    KSPDestroy(&t.normal);
  }
}

PetscErrorCode LevelHierarchy::least_squares_projection(int l, Vec fine, Vec coarse) const {
  PetscFunctionBeginUser;
  Transfer& t = transfers_[l];
  if (!t.normal) {
    PetscCall(MatTransposeMatMult(t.S, t.S, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t.StS));
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)t.S), &t.normal));
    PetscCall(KSPSetOptionsPrefix(t.normal, "mlshell_lsq_"));
    PetscCall(KSPSetOperators(t.normal, t.StS, t.StS));
    PetscCall(KSPSetType(t.normal, KSPPREONLY));
    PC pc;
    PetscCall(KSPGetPC(t.normal, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PetscCall(KSPSetFromOptions(t.normal));
  }
  Vec rhs;
  PetscCall(VecDuplicate(coarse, &rhs));
  PetscCall(MatMult(t.R, fine, rhs));
  PetscCall(KSPSolve(t.normal, rhs, coarse));
  PetscCall(VecDestroy(&rhs));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
