// Triangle levels from decimation hierarchies (paper 2 §4.1–4.3), as TriangleLevels assembles
// them: every level's rest shape recovered by P_{l+1}^l and by the direct P^l (a dome, a sphere,
// an unstructured embossed plate and an OBJ with two holes); on a flat hierarchy U is a
// partition of unity with one coarse triangle per row and P adds no normal offset; rigid
// motions commute with every prolongation; coarse levels are distributed from the finest
// partition, and the Galerkin pairs hold the coupling of J_Pᵀ H J_P.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include "mlshell/triangle/triangle_generators.hpp"
#include "mlshell/triangle/triangle_levels.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"
#include "triangle/triangle_fixtures.hpp"

using namespace mlshell;

namespace {

/// A unit square (unstructured, edge 0.03) with two round holes, written as an OBJ file and
/// read back as a user's mesh would be.
TriangleMesh obj_with_two_holes() {
  const TriangleMesh plate = make_unstructured_rectangle(1.0, 1.0, 0.03);
  const auto file = std::filesystem::temp_directory_path() /
                    ("mlshell_holes_" + std::to_string(getpid()) + ".obj");
  {
    std::ofstream obj(file);
    obj.precision(17);
    std::vector<int> index(plate.points.size(), 0);
    std::vector<Triangle> kept;
    for (const Triangle& t : plate.triangles) {
      const Point3 c = (plate.points[t[0]] + plate.points[t[1]] + plate.points[t[2]]) / 3.0;
      if ((c - Point3(0.3, 0.35, 0)).norm() < 0.12 || (c - Point3(0.7, 0.6, 0)).norm() < 0.15)
        continue;
      kept.push_back(t);
      for (int v : t) index[v] = 1;
    }
    int used = 0;
    for (size_t v = 0; v < plate.points.size(); ++v) {
      if (!index[v]) continue;
      index[v] = ++used;  // OBJ numbers from 1
      const Point3& p = plate.points[v];
      obj << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    for (const Triangle& t : kept)
      obj << "f " << index[t[0]] << ' ' << index[t[1]] << ' ' << index[t[2]] << '\n';
  }
  TriangleMesh mesh = read_obj_triangles(file);
  std::filesystem::remove(file);
  return mesh;
}

/// An unstructured unit square embossed with 3 × 2 bumps of 0.08 (detail the coarse levels
/// cannot hold).
TriangleMesh embossed_plate() {
  TriangleMesh m = make_unstructured_rectangle(1.0, 1.0, 0.04);
  for (Point3& p : m.points)
    p.z() = 0.08 * std::pow(std::sin(3 * std::numbers::pi * p.x()), 2) *
            std::pow(std::sin(2 * std::numbers::pi * p.y()), 2);
  return m;
}

TriangleLevels three_levels(const TriangleMesh& fine) {
  auto h = std::make_shared<const DecimationHierarchy>(
      decimate(fine, DecimationOptions::by_ratio(fine.num_points(), 3, 3.0)));
  return TriangleLevels(PETSC_COMM_WORLD, h);
}

const std::vector<Point3>& rest(const TriangleLevels& levels, int l) {
  return levels.discretization(l).mesh().points;
}

}  // namespace

TEST(TriangleLevels, EveryLevelRecoversTheFinestRestShapeDirectlyAndThroughItsNeighbour) {
  const std::pair<const char*, TriangleMesh> cases[] = {
      {"dome", make_spherical_cap(1.0, 1.0, 16)},
      {"sphere", make_sphere(1.0, 3)},
      {"embossed plate", embossed_plate()},
      {"OBJ with two holes", obj_with_two_holes()}};
  for (const auto& [name, fine] : cases) {
    SCOPED_TRACE(name);
    const TriangleLevels levels = three_levels(fine);
    ASSERT_EQ(levels.num_levels(), 3) << name;
    const int finest = levels.finest();
    for (int l = 0; l < finest; ++l) {
      EXPECT_LT(rest(levels, l).size(), rest(levels, l + 1).size()) << name;
      EXPECT_LT(rest_shape_error(levels.prolongation(l), rest(levels, l), rest(levels, l + 1)),
                1e-12)
          << name << ": P_" << l + 1 << "^" << l;
      EXPECT_LT(rest_shape_error(levels.direct_prolongation(l), rest(levels, l),
                                 rest(levels, finest)),
                1e-12)
          << name << ": direct P^" << l;
    }
  }
}

TEST(TriangleLevels, FlatLevelsProlongByAPartitionOfUnityWithoutNormalOffsets) {
  const TriangleLevels levels = three_levels(make_unstructured_rectangle(1.0, 1.0, 0.04));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.2, 0.2);
  for (int l = 0; l < levels.finest(); ++l)
    for (const ShellProlongation* p : {&levels.prolongation(l), &levels.direct_prolongation(l)}) {
      std::vector<Point3> x = rest(levels, l);
      for (Point3& q : x) q += Point3(noise(rng), noise(rng), noise(rng));
      const std::vector<Point3> px = p->apply(x);
      int offsets = 0;
      for (int i = 0; i < p->num_fine(); ++i) {
        const EmbeddedPoint& e = p->embedding(i);
        EXPECT_NEAR(e.weights[0] + e.weights[1] + e.weights[2], 1.0, 1e-12);
        for (double w : e.weights) EXPECT_GE(w, -1e-12);
        EXPECT_NEAR(p->normal_offset(i), 0.0, 1e-14);
        if (p->tangent_offset(i).norm() > 1e-12) {
          // Only a vertex that survives into the coarse level, moved there by its collapse's
          // placement, keeps an offset: it rides on itself.
          ++offsets;
          EXPECT_NEAR(*std::max_element(e.weights.begin(), e.weights.end()), 1.0, 1e-12);
          continue;
        }
        Point3 ux = Point3::Zero();
        for (int k = 0; k < 3; ++k) ux += e.weights[k] * x[p->columns(i)[k]];
        EXPECT_LT((px[i] - ux).norm(), 1e-12) << "level " << l << ", fine vertex " << i;
      }
      EXPECT_LT(offsets, p->num_fine() / 2) << "level " << l;
    }
}

TEST(TriangleLevels, RigidMotionsCommuteWithEveryProlongation) {
  const TriangleLevels levels = three_levels(make_spherical_cap(1.0, 1.0, 16));
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Point3 c(0.3, -1.2, 2.0);
  auto moved = [&](const std::vector<Point3>& x) {
    std::vector<Point3> y = x;
    for (Point3& p : y) p = Q * p + c;
    return y;
  };
  const int finest = levels.finest();
  for (int l = 0; l < finest; ++l) {
    const std::vector<Point3> x = moved(rest(levels, l));
    const std::vector<Point3> next = moved(rest(levels, l + 1)), fine = moved(rest(levels, finest));
    const std::vector<Point3> p = levels.prolongation(l).apply(x);
    const std::vector<Point3> direct = levels.direct_prolongation(l).apply(x);
    for (size_t i = 0; i < p.size(); ++i) EXPECT_LT((p[i] - next[i]).norm(), 1e-12) << l;
    for (size_t i = 0; i < direct.size(); ++i) EXPECT_LT((direct[i] - fine[i]).norm(), 1e-12) << l;
  }
}

TEST(TriangleLevels, CoarseLevelsTakeTheOwnersOfTheVerticesTheyCarry) {
  // Two coarse triangles; finer vertices 0–3 are the coarse corners (each also embedded with
  // weight 1 in one triangle), 4–6 lie in triangle 0 and 7–8 in triangle 1. Triangle 0 has the
  // votes of its corners 0, 1, 2 and of 0, 1, 2, 4, 5, 6: rank 1 has six of nine. Triangle 1
  // has those of its corners 1, 3, 2 and of 3, 7, 8: three each, and the tie goes to rank 0.
  TriangleMesh coarse;
  coarse.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(1, 1, 0)};
  coarse.triangles = {{0, 1, 2}, {1, 3, 2}};
  const std::vector<EmbeddedPoint> embedding = {
      {0, {1, 0, 0}},       {0, {0, 1, 0}},       {0, {0, 0, 1}},
      {1, {0, 1, 0}},       {0, {0.2, 0.3, 0.5}}, {0, {0.5, 0.3, 0.2}},
      {0, {0.3, 0.3, 0.4}}, {1, {0.3, 0.3, 0.4}}, {1, {0.6, 0.2, 0.2}}};
  const std::vector<int> corner_of = {0, 1, 2, 3};
  const std::vector<int> owner = {0, 1, 1, 0, 1, 1, 0, 1, 0};
  EXPECT_EQ(inherited_face_owners(coarse, embedding, corner_of, owner, 2),
            (std::vector<int>{1, 0}));
}

TEST(TriangleLevels, GalerkinPairsCoupleCoarseVerticesWhoseTrianglesShareFineStencils) {
  const TriangleLevels levels = three_levels(make_spherical_cap(1.0, 1.0, 16));
  for (int l = 0; l < levels.finest(); ++l) {
    // Every coarse pair that J_P's rows of two coupled finer points touch is in one of level
    // l's element stencils or among its Galerkin pairs; the finer points are coupled by an
    // element stencil of level l + 1 or, below the finest, by its own Galerkin pairs.
    auto stencil_pairs = [](const TriangleDiscretization& d) {
      std::vector<std::array<int, 2>> pairs;
      for (int f : d.elements()) {
        const std::vector<int> st = d.stencil(f);
        for (int a : st)
          for (int b : st) pairs.push_back({a, b});
      }
      return pairs;
    };
    std::set<std::array<int, 2>> coupled;
    for (const auto& [a, b] : stencil_pairs(levels.discretization(l)))
      coupled.insert({std::min(a, b), std::max(a, b)});
    for (const auto& pair : levels.galerkin_pairs(l)) coupled.insert(pair);
    std::vector<std::array<int, 2>> fine_pairs = stencil_pairs(levels.discretization(l + 1));
    if (l + 1 < levels.finest())
      fine_pairs.insert(fine_pairs.end(), levels.galerkin_pairs(l + 1).begin(),
                        levels.galerkin_pairs(l + 1).end());
    const ShellProlongation& p = levels.prolongation(l);
    int missing = 0;
    for (const auto& [i, j] : fine_pairs)
      for (int a : p.columns(i))
        for (int b : p.columns(j)) missing += !coupled.count({std::min(a, b), std::max(a, b)});
    EXPECT_EQ(missing, 0) << "level " << l;
    EXPECT_FALSE(levels.galerkin_pairs(l).empty()) << "level " << l;
  }
}
