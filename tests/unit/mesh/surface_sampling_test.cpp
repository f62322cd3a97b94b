// SurfaceSampling: every sample is its reference point plus the weighted displacements of its
// nodes, and inconsistent sizes are refused.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mlshell/discretization.hpp"

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
