// SurfaceSampling: every sample is its reference point plus the weighted displacements of its
// nodes, inconsistent sizes are refused, and the parts a discretization samples alone (one per
// rank) are, put together, its whole sampling.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mlshell/discretization.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

TEST(SurfaceSampling, PointsAreReferencePlusWeightedDisplacements) {
  // Sample 0 = ¼ node 0 + ¾ node 1, sample 1 = node 2; one triangle.
  const SurfaceSampling s({1, 2, 3, 4, 5, 6}, {0, 2, 3}, {0, 1, 2}, {0.25, 0.75, 1.0}, {0, 1, 1},
                          3);
  const std::vector<double> u = {4, 0, 0, 0, 8, 0, 0, 0, -1};
  const SurfaceSample out = s.sample(u);
  EXPECT_EQ(out.displacement, (std::vector<double>{1, 6, 0, 0, 0, -1}));
  EXPECT_EQ(out.points, (std::vector<double>{2, 8, 3, 4, 5, 5}));
  EXPECT_EQ(out.cells, (std::vector<std::int64_t>{0, 1, 1}));
  EXPECT_EQ(out.cell_size, 3);
  EXPECT_EQ(s.sample({}).points, (std::vector<double>{1, 2, 3, 4, 5, 6}));
}

TEST(SurfaceSampling, RejectsInconsistentSizes) {
  EXPECT_THROW(SurfaceSampling({1, 2, 3}, {0, 2}, {0}, {1.0}, {}, 3), std::invalid_argument);
  EXPECT_THROW(SurfaceSampling({1, 2}, {0, 1}, {0}, {1.0}, {}, 3), std::invalid_argument);
  EXPECT_THROW(SurfaceSampling({1, 2, 3}, {0, 1}, {0}, {1.0}, {0, 0, 1}, 3),
               std::invalid_argument);  // cell index 1 of 1 sample
}

namespace {

/// The parts' points, weights and cells put together, checking that each part starts where the
/// one before it ended.
void expect_parts_make_the_whole(const SurfaceSampling& whole,
                                 const std::vector<std::unique_ptr<SurfaceSampling>>& parts) {
  std::vector<double> reference, weights;
  std::vector<int> nodes;
  std::vector<std::int64_t> cells, lengths;
  std::int64_t points = 0, cell_count = 0;
  for (const auto& part : parts) {
    EXPECT_EQ(part->place().first_point, points);
    EXPECT_EQ(part->place().first_cell, cell_count);
    EXPECT_EQ(part->place().total_points, whole.num_points());
    EXPECT_EQ(part->place().total_cells, whole.num_cells());
    points += part->num_points();
    cell_count += part->num_cells();
    reference.insert(reference.end(), part->reference().begin(), part->reference().end());
    weights.insert(weights.end(), part->weights().begin(), part->weights().end());
    nodes.insert(nodes.end(), part->nodes().begin(), part->nodes().end());
    cells.insert(cells.end(), part->cells().begin(), part->cells().end());
    for (std::int64_t p = 0; p < part->num_points(); ++p)
      lengths.push_back(part->offsets()[p + 1] - part->offsets()[p]);
  }
  std::vector<std::int64_t> whole_lengths;
  for (std::int64_t p = 0; p < whole.num_points(); ++p)
    whole_lengths.push_back(whole.offsets()[p + 1] - whole.offsets()[p]);
  EXPECT_EQ(reference, whole.reference());
  EXPECT_EQ(weights, whole.weights());
  EXPECT_EQ(nodes, whole.nodes());
  EXPECT_EQ(cells, whole.cells());
  EXPECT_EQ(lengths, whole_lengths);
}

}  // namespace

TEST(SurfaceSampling, SlicesPutTogetherAreTheWhole) {
  TestProblem tp("extraordinary", PETSC_COMM_SELF);
  const auto whole = tp.disc->sampling(3);
  std::vector<std::unique_ptr<SurfaceSampling>> slices;
  for (int i = 0; i < 3; ++i) slices.push_back(whole->slice(i, 3));
  expect_parts_make_the_whole(*whole, slices);
  EXPECT_THROW(slices[1]->slice(0, 2), std::logic_error) << "a slice of a slice";
}

TEST(SurfaceSampling, SubdivisionPartsSampledAloneAreTheWhole) {
  // Each rank samples only its elements and the points they own
  // (SubdivisionDiscretization::sampling_part); an uneven split, with a cage face at an
  // extraordinary vertex.
  TestProblem tp("extraordinary", PETSC_COMM_SELF);
  for (int k : {1, 3}) {
    const auto whole = tp.disc->sampling(k);
    std::vector<std::unique_ptr<SurfaceSampling>> parts;
    for (int i = 0; i < 7; ++i) parts.push_back(tp.disc->sampling_part(k, i, 7));
    EXPECT_NE(parts[0]->num_points(), parts[6]->num_points()) << "the split is even";
    expect_parts_make_the_whole(*whole, parts);
  }
}
