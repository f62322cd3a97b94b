// The levels of a triangle-mesh shell (see triangle_levels.hpp).
#include "mlshell/triangle/triangle_levels.hpp"

#include <mpi.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

#include "mlshell/decimation/intrinsic_embedding.hpp"
#include "mlshell/prolongation/triangle_transfer.hpp"

namespace mlshell {

namespace {

/// For every vertex of `coarse`, the vertex of `fine` that is the same finest-mesh vertex.
std::vector<int> corners_in_finer(const DecimationLevel& coarse, const DecimationLevel& fine) {
  const int n = fine.finest_vertex.empty() ? 0 : fine.finest_vertex.back() + 1;
  std::vector<int> of_finest(n, -1);
  for (int v = 0; v < static_cast<int>(fine.finest_vertex.size()); ++v)
    of_finest[fine.finest_vertex[v]] = v;
  std::vector<int> corner_of(coarse.finest_vertex.size());
  for (size_t k = 0; k < corner_of.size(); ++k) {
    const int f = coarse.finest_vertex[k];
    if (f >= n || of_finest[f] < 0)
      throw std::logic_error("decimation: a coarse vertex is missing from the finer level");
    corner_of[k] = of_finest[f];
  }
  return corner_of;
}

}  // namespace

std::vector<int> point_owners(const ParallelLayout& layout) {
  std::vector<int> first(layout.size() + 1, 0);
  const int owned = layout.num_owned_points();
  MPI_Allgather(&owned, 1, MPI_INT, first.data() + 1, 1, MPI_INT, layout.comm());
  for (int r = 0; r < layout.size(); ++r) first[r + 1] += first[r];
  std::vector<int> owner(first.back());  // every point is owned once
  for (int p = 0; p < first.back(); ++p)
    owner[p] = static_cast<int>(std::upper_bound(first.begin(), first.end(), layout.petsc_of(p)) -
                                first.begin()) -
               1;
  return owner;
}

std::vector<int> inherited_face_owners(const TriangleMesh& coarse,
                                       const std::vector<EmbeddedPoint>& embedding,
                                       const std::vector<int>& corner_of,
                                       const std::vector<int>& finer_point_owner, int num_ranks) {
  std::vector<int> votes(static_cast<size_t>(coarse.num_triangles()) * num_ranks, 0);
  for (int t = 0; t < coarse.num_triangles(); ++t)
    for (int k : coarse.triangles[t]) ++votes[t * num_ranks + finer_point_owner[corner_of[k]]];
  for (size_t i = 0; i < embedding.size(); ++i)
    ++votes[embedding[i].triangle * num_ranks + finer_point_owner[i]];
  std::vector<int> owner(coarse.num_triangles());
  for (int t = 0; t < coarse.num_triangles(); ++t) {
    const auto first = votes.begin() + static_cast<long>(t) * num_ranks;
    owner[t] = static_cast<int>(std::max_element(first, first + num_ranks) - first);
  }
  return owner;
}

TriangleLevels::TriangleLevels(MPI_Comm comm, TriangleMesh mesh) {
  discs_.push_back(std::make_unique<TriangleDiscretization>(std::move(mesh)));
  layouts_.push_back(std::make_unique<ParallelLayout>(comm, *discs_.back()));
}

TriangleLevels::TriangleLevels(MPI_Comm comm, std::shared_ptr<const DecimationHierarchy> hierarchy,
                               int coarsest)
    : hierarchy_(std::move(hierarchy)), first_(coarsest) {
  const int top = hierarchy_->num_levels() - 1;
  if (coarsest < 0 || coarsest > top)
    throw std::invalid_argument("TriangleLevels: no level " + std::to_string(coarsest));
  // Every rank decimated the same mesh: check that they agree before distributing anything.
  const std::string mine = hierarchy_->fingerprint();
  std::string root = mine;
  root.resize(64, '\0');
  MPI_Bcast(root.data(), 64, MPI_CHAR, 0, comm);
  int differs = root.substr(0, mine.size()) != mine ? 1 : 0, any = 0;
  MPI_Allreduce(&differs, &any, 1, MPI_INT, MPI_MAX, comm);
  if (any) throw std::runtime_error("decimation: the ranks built different hierarchies");

  const int n = top - coarsest + 1;
  discs_.resize(n);
  layouts_.resize(n);
  prolongations_.resize(n - 1);
  transfers_.resize(n - 1);
  direct_.resize(n);
  for (int l = 0; l < n; ++l)
    discs_[l] = std::make_unique<TriangleDiscretization>(hierarchy_->levels[first_ + l].mesh);
  layouts_[n - 1] = std::make_unique<ParallelLayout>(comm, *discs_[n - 1]);
  int size = 1;
  MPI_Comm_size(comm, &size);
  for (int l = n - 2; l >= 0; --l) {
    const DecimationLevel& coarse = hierarchy_->levels[first_ + l];
    const DecimationLevel& fine = hierarchy_->levels[first_ + l + 1];
    std::vector<EmbeddedPoint> embedding =
        intrinsic_embedding(*hierarchy_, first_ + l, first_ + l + 1);
    const std::vector<int> corner_of = corners_in_finer(coarse, fine);
    layouts_[l] = std::make_unique<ParallelLayout>(
        comm, *discs_[l],
        inherited_face_owners(coarse.mesh, embedding, corner_of, point_owners(*layouts_[l + 1]),
                              size));
    prolongations_[l] = std::make_shared<ShellProlongation>(coarse.mesh, fine.mesh.points,
                                                            std::move(embedding));
    const double cost =
        static_cast<double>(coarse.mesh.num_triangles()) / fine.mesh.num_triangles();
    transfers_[l] = std::make_unique<ShellTransfer>(*layouts_[l], *layouts_[l + 1],
                                                    prolongations_[l], cost, corner_of);
  }
  find_galerkin_pairs();
}

TriangleLevels::~TriangleLevels() = default;

void TriangleLevels::find_galerkin_pairs() {
  // Sorted neighbour lists per point, the point itself included.
  auto stencil_adjacency = [](const TriangleDiscretization& d) {
    std::vector<std::vector<int>> adj(d.num_points());
    for (int f : d.elements()) {
      const std::vector<int> st = d.stencil(f);
      for (int a : st) adj[a].insert(adj[a].end(), st.begin(), st.end());
    }
    for (auto& a : adj) {
      std::sort(a.begin(), a.end());
      a.erase(std::unique(a.begin(), a.end()), a.end());
    }
    return adj;
  };
  const int n = num_levels();
  galerkin_pairs_.assign(std::max(n - 1, 0), {});
  std::vector<std::vector<int>> fine = stencil_adjacency(*discs_[n - 1]);
  for (int l = n - 2; l >= 0; --l) {
    const ShellProlongation& p = *prolongations_[l];
    std::vector<std::vector<int>> coarse(discs_[l]->num_points());
    for (int i = 0; i < p.num_fine(); ++i)
      for (int j : fine[i])
        for (int a : p.columns(i))
          coarse[a].insert(coarse[a].end(), p.columns(j).begin(), p.columns(j).end());
    const std::vector<std::vector<int>> own = stencil_adjacency(*discs_[l]);
    for (int a = 0; a < static_cast<int>(coarse.size()); ++a) {
      std::vector<int>& c = coarse[a];
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end()), c.end());
      for (int b : c)
        if (a < b && !std::binary_search(own[a].begin(), own[a].end(), b))
          galerkin_pairs_[l].push_back({a, b});
      // The level's matrices hold both patterns.
      std::vector<int> both;
      std::set_union(c.begin(), c.end(), own[a].begin(), own[a].end(), std::back_inserter(both));
      c = std::move(both);
    }
    fine = std::move(coarse);
  }
}

const LevelTransfer& TriangleLevels::transfer(int l) const {
  if (l < 0 || l >= static_cast<int>(transfers_.size()))
    throw std::logic_error("TriangleLevels: no transfer between levels " + std::to_string(l) +
                           " and " + std::to_string(l + 1) + " (" +
                           std::to_string(num_levels()) + " level(s))");
  return *transfers_[l];
}

const ShellProlongation& TriangleLevels::direct_prolongation(int l) const {
  if (!hierarchy_ || l < 0 || l >= finest())
    throw std::logic_error("TriangleLevels: no direct prolongation from level " +
                           std::to_string(l));
  if (!direct_[l]) {
    const int top = hierarchy_->num_levels() - 1;
    direct_[l] = std::make_shared<const ShellProlongation>(
        hierarchy_->levels[first_ + l].mesh, hierarchy_->levels[top].mesh.points,
        intrinsic_embedding(*hierarchy_, first_ + l, top));
  }
  return *direct_[l];
}

const LevelTransfer& TriangleLevels::direct_transfer(int l) const {
  direct_prolongation(l);  // checks l
  if (direct_transfers_.empty()) direct_transfers_.resize(num_levels());
  if (!direct_transfers_[l]) {
    const int top = hierarchy_->num_levels() - 1;
    const DecimationLevel& coarse = hierarchy_->levels[first_ + l];
    const double cost = static_cast<double>(coarse.mesh.num_triangles()) /
                        hierarchy_->levels[top].mesh.num_triangles();
    direct_transfers_[l] = std::make_unique<ShellTransfer>(
        *layouts_[l], *layouts_[finest()], direct_[l], cost,
        corners_in_finer(coarse, hierarchy_->levels[top]));
  }
  return *direct_transfers_[l];
}

}  // namespace mlshell
