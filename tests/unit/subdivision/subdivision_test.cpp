// Cages, ghost rings, uniform refinement and limit-surface basis functions.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "mlshell/subdivision/subdivision_discretization.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "opensubdiv_reference.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

QuadMesh square_cage(int n) {
  return add_ghost_ring(make_rectangle_cage(1.0, 1.0, n, n, 0.0, 0.0));
}

}  // namespace

TEST(Subdivision, PaperDofCountsForFourByFourSquare) {
  const int expected[] = {147, 363, 1083, 3675, 13467, 51483};
  SubdivisionHierarchy h(square_cage(4), 5);
  for (int l = 0; l <= 5; ++l) EXPECT_EQ(3 * h.level(l).num_points(), expected[l]) << "level " << l;
}

TEST(Subdivision, SubdivisionMatrixIsOpenSubdivsRefinement) {
  // Rows of S sum to one, and S applied to the (randomly perturbed, non-planar) control points
  // of each level gives points of OpenSubdiv's own refinement of the whole cage.
  QuadMesh cage = add_ghost_ring(make_l_shape_cage(1, 1, 10, 10, 0.3, 0.3, 0, 0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (Point3& p : cage.points) p += Point3(jitter(rng), jitter(rng), 5 * jitter(rng));
  SubdivisionHierarchy h(cage, 2);
  const auto reference = opensubdiv_levels(cage, 2);
  for (int l = 0; l < 2; ++l) {
    const auto& S = h.subdivision(l);
    for (int i = 0; i < S.rows(); ++i) EXPECT_NEAR(S.row(i).sum(), 1.0, 1e-14);
    Eigen::MatrixXd X(h.level(l).num_points(), 3);
    for (int i = 0; i < X.rows(); ++i) X.row(i) = h.level(l).points[i].transpose();
    const Eigen::MatrixXd Y = S * X;
    std::vector<Point3> refined;
    for (int i = 0; i < Y.rows(); ++i) refined.emplace_back(Y.row(i).transpose());
    EXPECT_LT(farthest_from(refined, reference[l + 1]), 1e-13) << "level " << l;
  }
}

TEST(Subdivision, GeneratedCagesAreAllRegular) {
  for (const QuadMesh& cage :
       {square_cage(4), add_ghost_ring(make_l_shape_cage(1, 1, 10, 10, 0.3, 0.3, 0, 0))}) {
    SubdivisionDiscretization d(SubdivisionHierarchy(cage, 1).finest(), 3);
    EXPECT_EQ(d.evaluator().num_irregular_faces(), 0);
  }
}

TEST(Subdivision, RegularBasisIsPartitionOfUnityWithLinearPrecision) {
  // On an affinely mapped cage the limit surface is the same affine map of the parameter plane
  // (Catmull–Clark reproduces linear functions): check values and derivatives on every face.
  QuadMesh cage = add_ghost_ring(make_rectangle_cage(2.0, 1.0, 4, 4, 0.0, 0.0));
  Eigen::Matrix3d A;
  A << 1.0, 0.3, 0.0, -0.2, 0.9, 0.0, 0.1, 0.05, 1.0;
  for (Point3& p : cage.points) p = A * p;
  SubdivisionDiscretization d(SubdivisionHierarchy(cage, 1).finest(), 3);
  const double h = 2.0 / 8, k = 1.0 / 8;  // refined face size in the parameter plane
  for (int f : d.elements()) {
    const SurfacePoint p{f, 0.3, 0.7};
    const PointBasis b = d.evaluator().evaluate({p})[0];
    double sum = 0.0, dsum = 0.0;
    for (int i = 0; i < b.size(); ++i) {
      sum += b.w[kValue][i];
      for (int dd = kDu; dd <= kDvv; ++dd) dsum += b.w[dd][i];  // derivatives of a constant
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_NEAR(dsum, 0.0, 1e-12);
    // Corner 0 of the face and its edge directions in the (unmapped) plane.
    const Quad& q = d.mesh().quads[f];
    const Point3 x0 = d.mesh().points[q[0]];
    const Point3 eu = d.mesh().points[q[1]] - x0, ev = d.mesh().points[q[3]] - x0;
    EXPECT_LT((b.apply(kValue, d.mesh().points) - (x0 + 0.3 * eu + 0.7 * ev)).norm(), 1e-13);
    EXPECT_LT((b.apply(kDu, d.mesh().points) - eu).norm(), 1e-13);
    EXPECT_LT((b.apply(kDv, d.mesh().points) - ev).norm(), 1e-13);
    EXPECT_LT(b.apply(kDuv, d.mesh().points).norm(), 1e-12);
    EXPECT_NEAR(eu.norm(), (A * Point3(h, 0, 0)).norm(), 1e-13);
    EXPECT_NEAR(ev.norm(), (A * Point3(0, k, 0)).norm(), 1e-13);
  }
}

TEST(Subdivision, LimitStencilsAreSmoothAcrossRegularAndIrregularFaces) {
  for (int valence : {3, 5, 6, 8}) {
    QuadMesh mesh = SubdivisionHierarchy(add_ghost_ring(fan_cage(valence)), 1).finest();
    SubdivisionDiscretization d(mesh, 3);
    const LimitEvaluator& eval = d.evaluator();
    ASSERT_GT(eval.num_irregular_faces(), 0) << valence;
    // Position and tangent continuity across every interior edge between two interior faces:
    // evaluate both sides at the edge midpoint.
    const QuadAdjacency adj(mesh);
    int checked = 0;
    for (int f : d.elements())
      for (int k = 0; k < 4; ++k) {
        const int g = adj.across(f, k);
        if (g < 0 || mesh.is_ghost(g)) continue;
        const Quad& F = mesh.quads[f];
        const Quad& G = mesh.quads[g];
        int m = 0;
        while (G[m] != F[(k + 1) % 4]) ++m;
        const SurfacePoint pf = d.edge_point({f, k}, 0.37);
        const SurfacePoint pg = d.edge_point({g, m}, 0.63);
        const auto b = eval.evaluate({pf, pg});
        const Point3 xf = b[0].apply(kValue, mesh.points), xg = b[1].apply(kValue, mesh.points);
        EXPECT_LT((xf - xg).norm(), 1e-12) << "valence " << valence << " face " << f;
        // Tangent planes agree (G1): normals parallel.
        const Point3 nf =
            b[0].apply(kDu, mesh.points).cross(b[0].apply(kDv, mesh.points)).normalized();
        const Point3 ng =
            b[1].apply(kDu, mesh.points).cross(b[1].apply(kDv, mesh.points)).normalized();
        EXPECT_GT(nf.dot(ng), 1.0 - 1e-10) << "valence " << valence;
        double sum = 0;
        for (double x : b[0].w[kValue]) sum += x;
        EXPECT_NEAR(sum, 1.0, 1e-12);
        ++checked;
      }
    EXPECT_GT(checked, 10);
  }
}

TEST(Subdivision, ValueOnlyEvaluationGivesTheSameValueWeights) {
  // Output sampling and bounding boxes evaluate values only: the same nodes and value weights
  // as the full evaluation (to round-off on faces at an extraordinary vertex, whose OpenSubdiv
  // stencils are then built without derivatives), and no derivative slots.
  for (int valence : {4, 5}) {
    const QuadMesh mesh = SubdivisionHierarchy(add_ghost_ring(fan_cage(valence)), 1).finest();
    const SubdivisionDiscretization d(mesh, 3);
    std::vector<SurfacePoint> points;
    for (int f : d.elements())
      for (double u : {0.0, 0.3, 1.0}) points.push_back({f, u, 1.0 - 0.6 * u});
    const auto all = d.evaluator().evaluate(points);
    const auto values = d.evaluator().evaluate(points, BasisSlots::kValueOnly);
    ASSERT_EQ(values.size(), points.size());
    int irregular = 0;
    for (size_t p = 0; p < points.size(); ++p) {
      irregular += !d.evaluator().is_regular(points[p].face) ? 1 : 0;
      for (int s = kDu; s <= kDvv; ++s) EXPECT_TRUE(values[p].w[s].empty());
      const Point3 x = all[p].apply(kValue, mesh.points), y = values[p].apply(kValue, mesh.points);
      EXPECT_LT((x - y).norm(), 1e-14) << "valence " << valence << " point " << p;
      std::map<int, double> a, b;
      for (int i = 0; i < all[p].size(); ++i) a[all[p].nodes[i]] += all[p].w[kValue][i];
      for (int i = 0; i < values[p].size(); ++i) b[values[p].nodes[i]] += values[p].w[kValue][i];
      for (const auto& [node, w] : a) EXPECT_NEAR(b[node], w, 1e-14) << "node " << node;
      for (const auto& [node, w] : b) EXPECT_NEAR(a[node], w, 1e-14) << "node " << node;
    }
    EXPECT_GT(irregular, 0) << "valence " << valence;  // both code paths
    EXPECT_LT(irregular, static_cast<int>(points.size())) << "valence " << valence;
  }
}

TEST(Subdivision, LShapeGhostRingFillsTheNotch) {
  QuadMesh m = add_ghost_ring(make_l_shape_cage(1, 1, 10, 10, 0.3, 0.3, 0, 0));
  // 100 - 9 interior faces; ghost faces: the boundary has 40 edges, 5 convex corners add one
  // face each, the re-entrant corner merges two edge faces into one.
  int ghosts = 0;
  for (int f = 0; f < m.num_faces(); ++f) ghosts += m.is_ghost(f);
  EXPECT_EQ(m.num_faces() - ghosts, 91);
  EXPECT_EQ(ghosts, 40 + 5 - 1);
}

TEST(Subdivision, RejectsBrokenCages) {
  QuadMesh m = make_rectangle_cage(1, 1, 2, 1, 0, 0);
  m.quads[1] = {m.quads[0][1], m.quads[0][0], m.quads[1][2], m.quads[1][3]};  // flipped edge use
  EXPECT_THROW(validate_quad_mesh(m, "x"), MeshError);
  QuadMesh d = make_rectangle_cage(1, 1, 1, 1, 0, 0);
  d.quads[0][2] = d.quads[0][0];
  EXPECT_THROW(validate_quad_mesh(d, "x"), MeshError);
}
