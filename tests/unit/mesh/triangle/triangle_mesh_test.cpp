// Triangle mesh topology (edges, hinges, fans, boundary loops), validation and the OBJ reader.
#include "mlshell/triangle/triangle_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include "mlshell/triangle/triangle_generators.hpp"

using namespace mlshell;

namespace {

/// The MeshError message of `f`, or "no error".
std::string mesh_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "no error";
}

std::string validation_error(const TriangleMesh& mesh) {
  return mesh_error([&] { validate_triangle_mesh(mesh, "test mesh"); });
}

/// Whether triangle t lists a, b, c in this cyclic order.
bool is_rotation_of(const Triangle& t, int a, int b, int c) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == a && t[(k + 1) % 3] == b && t[(k + 2) % 3] == c) return true;
  return false;
}

/// The unit square split along its 0–2 diagonal: vertices 0 (0,0), 1 (1,0), 2 (1,1), 3 (0,1).
TriangleMesh two_triangles() {
  TriangleMesh m;
  m.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0), Point3(0, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

/// A 3 × 1 strip of unit squares: bottom vertices 0..3, top 4..7, six triangles.
TriangleMesh strip() {
  TriangleMesh m;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) m.points.emplace_back(i, j, 0);
  for (int i = 0; i < 3; ++i) {
    m.triangles.push_back({i, i + 1, i + 5});
    m.triangles.push_back({i, i + 5, i + 4});
  }
  return m;
}

std::vector<TriangleMesh> sample_meshes() {
  return {two_triangles(),
          strip(),
          make_triangle_rectangle(2.0, 1.0, 4, 3, 0.0, 0.0),
          make_unstructured_rectangle(1.0, 1.0, 0.2, 0.0, 0.0),
          make_cylinder(1.0, 2.0, 8, 3),
          make_spherical_cap(1.0, 1.2, 4),
          make_sphere(1.0, 2)};
}

}  // namespace

TEST(TriangleMesh, TwoTrianglesTopology) {
  const TriangleTopology t(two_triangles());
  ASSERT_EQ(t.num_edges(), 5);
  EXPECT_EQ(t.euler_characteristic(), 1);
  // Edges in lexicographic order of their sorted vertices: 0-1, 0-2, 0-3, 1-2, 2-3.
  const TriangleEdge& diagonal = t.edge(1);
  EXPECT_EQ(diagonal.v, (std::array<int, 2>{2, 0}));  // its direction in face 0 = (0, 1, 2)
  EXPECT_EQ(diagonal.faces, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(diagonal.local, (std::array<int, 2>{2, 0}));
  EXPECT_FALSE(diagonal.on_boundary());
  EXPECT_EQ(t.edge(2).v, (std::array<int, 2>{3, 0}));
  EXPECT_TRUE(t.edge(2).on_boundary());
  EXPECT_EQ(t.edge(2).faces[1], -1);
  ASSERT_EQ(t.hinges().size(), 1u);
  EXPECT_EQ(t.hinges()[0].v, (std::array<int, 4>{2, 0, 1, 3}));
  EXPECT_EQ(t.hinges()[0].faces, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(t.hinge_edges(), std::vector<int>{1});
  EXPECT_EQ(t.triangle_edges(0), (std::array<int, 3>{0, 3, 1}));
  EXPECT_EQ(t.neighbours(0), (std::array<int, 3>{-1, -1, 1}));
  EXPECT_EQ(t.neighbours(1), (std::array<int, 3>{0, -1, -1}));
  ASSERT_EQ(t.boundary_loops().size(), 1u);
  EXPECT_EQ(t.boundary_loops()[0], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(t.closed());
  EXPECT_EQ(t.boundary_vertices(), (std::vector<char>{1, 1, 1, 1}));
  // Vertex 0: counter-clockwise from the face whose edge leaving 0 is on the boundary.
  EXPECT_EQ(t.vertex_triangles(0), (std::vector<int>{0, 1}));
  EXPECT_EQ(t.vertex_triangles(2), (std::vector<int>{1, 0}));
  EXPECT_EQ(t.vertex_triangles(3), std::vector<int>{1});
}

TEST(TriangleMesh, HingeConventionOnEveryInteriorEdge) {
  for (const TriangleMesh& mesh : sample_meshes()) {
    const TriangleTopology t(mesh);
    ASSERT_EQ(t.hinges().size(), t.hinge_edges().size());
    int interior = 0;
    for (const TriangleEdge& e : t.edges()) interior += e.on_boundary() ? 0 : 1;
    EXPECT_EQ(static_cast<int>(t.hinges().size()), interior);
    for (size_t h = 0; h < t.hinges().size(); ++h) {
      const Hinge& hinge = t.hinges()[h];
      const auto& v = hinge.v;
      EXPECT_TRUE(is_rotation_of(mesh.triangles[hinge.faces[0]], v[0], v[1], v[2])) << h;
      EXPECT_TRUE(is_rotation_of(mesh.triangles[hinge.faces[1]], v[1], v[0], v[3])) << h;
      const TriangleEdge& e = t.edge(t.hinge_edges()[h]);
      EXPECT_EQ(e.faces, hinge.faces);
      EXPECT_EQ(e.v[0], v[0]);
      EXPECT_EQ(e.v[1], v[1]);
    }
  }
}

TEST(TriangleMesh, HingeWingsLieBelowEachOtherOnConvexSurface) {
  // On the outward-oriented sphere each wing vertex lies inside the other face's plane.
  const TriangleMesh mesh = make_sphere(1.0, 2);
  const auto& x = mesh.points;
  const TriangleTopology topology(mesh);
  for (const Hinge& h : topology.hinges()) {
    const Point3 n0 = (x[h.v[1]] - x[h.v[0]]).cross(x[h.v[2]] - x[h.v[0]]);
    const Point3 n1 = (x[h.v[0]] - x[h.v[1]]).cross(x[h.v[3]] - x[h.v[1]]);
    EXPECT_LT(n0.dot(x[h.v[3]] - x[h.v[0]]), 0.0);
    EXPECT_LT(n1.dot(x[h.v[2]] - x[h.v[0]]), 0.0);
  }
}

TEST(TriangleMesh, EdgesAndNeighboursAgree) {
  for (const TriangleMesh& mesh : sample_meshes()) {
    const TriangleTopology t(mesh);
    for (int f = 0; f < mesh.num_triangles(); ++f)
      for (int k = 0; k < 3; ++k) {
        const TriangleEdge& e = t.edge(t.triangle_edges(f)[k]);
        const int a = mesh.triangles[f][k], b = mesh.triangles[f][(k + 1) % 3];
        const int side = e.faces[0] == f ? 0 : 1;
        ASSERT_EQ(e.faces[side], f);
        EXPECT_EQ(e.local[side], k);
        EXPECT_EQ(side == 0 ? e.v : (std::array<int, 2>{e.v[1], e.v[0]}),
                  (std::array<int, 2>{a, b}));
        EXPECT_EQ(t.neighbour(f, k), e.faces[1 - side]);
        EXPECT_LT(e.faces[0], e.faces[1] < 0 ? mesh.num_triangles() : e.faces[1]);
      }
  }
}

TEST(TriangleMesh, VertexFansAreCounterClockwise) {
  for (const TriangleMesh& mesh : sample_meshes()) {
    const TriangleTopology t(mesh);
    std::vector<int> count(mesh.num_points(), 0);
    for (const Triangle& tri : mesh.triangles)
      for (int v : tri) ++count[v];
    for (int v = 0; v < mesh.num_points(); ++v) {
      const auto& fan = t.vertex_triangles(v);
      ASSERT_EQ(static_cast<int>(fan.size()), count[v]) << "vertex " << v;
      auto corner = [&](int f) {
        const Triangle& tri = mesh.triangles[f];
        return static_cast<int>(std::find(tri.begin(), tri.end(), v) - tri.begin());
      };
      for (size_t i = 0; i + 1 < fan.size(); ++i)
        EXPECT_EQ(t.neighbour(fan[i], (corner(fan[i]) + 2) % 3), fan[i + 1]) << "vertex " << v;
      if (t.on_boundary(v)) {
        EXPECT_EQ(t.neighbour(fan.front(), corner(fan.front())), -1) << "vertex " << v;
        EXPECT_EQ(t.neighbour(fan.back(), (corner(fan.back()) + 2) % 3), -1) << "vertex " << v;
      } else {
        EXPECT_EQ(t.neighbour(fan.back(), (corner(fan.back()) + 2) % 3), fan.front());
      }
    }
  }
}

TEST(TriangleMesh, BoundaryLoopsFollowBoundaryEdges) {
  for (const TriangleMesh& mesh : sample_meshes()) {
    const TriangleTopology t(mesh);
    std::map<std::pair<int, int>, int> boundary_edges;
    for (const TriangleEdge& e : t.edges())
      if (e.on_boundary()) boundary_edges[{e.v[0], e.v[1]}] = 0;
    size_t loop_vertices = 0;
    for (const auto& loop : t.boundary_loops()) {
      loop_vertices += loop.size();
      EXPECT_EQ(loop.front(), *std::min_element(loop.begin(), loop.end()));
      for (size_t i = 0; i < loop.size(); ++i) {
        auto it = boundary_edges.find({loop[i], loop[(i + 1) % loop.size()]});
        ASSERT_NE(it, boundary_edges.end()) << "loop step " << i << " is not a boundary edge";
        ++it->second;
      }
    }
    for (const auto& [e, uses] : boundary_edges) EXPECT_EQ(uses, 1);
    EXPECT_EQ(loop_vertices, boundary_edges.size());
    EXPECT_EQ(std::count(t.boundary_vertices().begin(), t.boundary_vertices().end(), 1),
              static_cast<long>(loop_vertices));
    EXPECT_EQ(t.closed(), boundary_edges.empty());
  }
}

TEST(TriangleMesh, BoundaryLoopOfStripIsCounterClockwise) {
  const TriangleTopology t(strip());
  ASSERT_EQ(t.boundary_loops().size(), 1u);
  EXPECT_EQ(t.boundary_loops()[0], (std::vector<int>{0, 1, 2, 3, 7, 6, 5, 4}));
  EXPECT_EQ(t.euler_characteristic(), 1);
}

TEST(TriangleMesh, ValidMeshesPass) {
  for (const TriangleMesh& mesh : sample_meshes()) EXPECT_EQ(validation_error(mesh), "no error");
}

TEST(TriangleMesh, RejectsEmptyMesh) {
  EXPECT_EQ(validation_error(TriangleMesh{}),
            "test mesh: the mesh has no triangles (expected at least one)");
}

TEST(TriangleMesh, RejectsIndexOutOfRange) {
  TriangleMesh m = two_triangles();
  m.triangles[1][2] = 4;
  EXPECT_EQ(validation_error(m),
            "test mesh: face 2 refers to vertex 5 but the mesh has 4 vertices");
  m.triangles[1][2] = -1;
  EXPECT_NE(validation_error(m).find("face 2 refers to vertex 0 but"), std::string::npos);
}

TEST(TriangleMesh, RejectsRepeatedVertex) {
  TriangleMesh m = two_triangles();
  m.triangles[0] = {0, 1, 1};
  EXPECT_EQ(validation_error(m),
            "test mesh: face 1 has vertex 2 twice (expected three distinct vertices)");
  m.triangles[0] = {2, 1, 2};
  EXPECT_NE(validation_error(m).find("face 1 has vertex 3 twice"), std::string::npos);
}

TEST(TriangleMesh, RejectsNonFiniteCoordinates) {
  TriangleMesh m = two_triangles();
  m.points[2].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(m),
            "test mesh: vertex 3 has a non-finite coordinate (1, inf, 0); expected finite numbers");
}

TEST(TriangleMesh, DegeneracyTestIsScaleFree) {
  // Well-shaped triangles pass at any size and distance from the origin.
  for (double scale : {1e-9, 1.0, 1e9}) {
    TriangleMesh m = two_triangles();
    for (Point3& p : m.points) p = scale * p + Point3(1e3 * scale, 0, 0);
    EXPECT_EQ(validation_error(m), "no error") << "scale " << scale;
  }
  // A sliver whose height is 1e-13 of its length fails at any size; 1e-10 passes.
  for (double scale : {1e-9, 1.0, 1e9}) {
    for (double height : {1e-13, 1e-10}) {
      TriangleMesh m;
      m.points = {Point3(0, 0, 0), Point3(scale, 0, 0), Point3(0.5 * scale, height * scale, 0)};
      m.triangles = {{0, 1, 2}};
      const std::string error = validation_error(m);
      if (height < 1e-12)
        EXPECT_EQ(error,
                  "test mesh: face 1 (vertices 1 2 3) is degenerate: zero area (its vertices are "
                  "collinear or coincide)")
            << "scale " << scale;
      else
        EXPECT_EQ(error, "no error") << "scale " << scale;
    }
  }
  TriangleMesh coincident = two_triangles();
  coincident.points[3] = coincident.points[0];
  EXPECT_NE(validation_error(coincident).find("face 2 (vertices 1 3 4) is degenerate"),
            std::string::npos);
}

TEST(TriangleMesh, RejectsDuplicateFaces) {
  TriangleMesh m = two_triangles();
  m.triangles.push_back({2, 0, 3});  // face 2 with the opposite orientation
  EXPECT_EQ(validation_error(m),
            "test mesh: face 3 repeats face 2: same vertices 3 1 4 (duplicate face)");
}

TEST(TriangleMesh, RejectsNonManifoldEdge) {
  TriangleMesh m = two_triangles();
  m.points.emplace_back(0.5, 0.5, 1.0);
  m.triangles.push_back({0, 2, 4});
  EXPECT_EQ(validation_error(m),
            "test mesh: face 3 makes edge 1-3 non-manifold: it is shared by face 1, face 2 and "
            "face 3 (expected at most two faces per edge)");
}

TEST(TriangleMesh, BlamesTheFlippedFace) {
  TriangleMesh m = strip();
  std::swap(m.triangles[2][1], m.triangles[2][2]);  // flip the third of six triangles
  // Face 3 disagrees with both its neighbours, faces 4 and 6, each of which disagrees only with it.
  EXPECT_EQ(validation_error(m),
            "test mesh: face 3 is flipped relative to face 4: both run edge 2->7 in the same "
            "direction (expected consistently oriented faces)");
  // Face 2 has a single neighbour, face 1: a tie, blamed on the later face.
  TriangleMesh second = strip();
  std::swap(second.triangles[1][1], second.triangles[1][2]);
  EXPECT_NE(validation_error(second).find("face 2 is flipped relative to face 1"),
            std::string::npos)
      << validation_error(second);
}

TEST(TriangleMesh, RejectsUnusedVertex) {
  TriangleMesh m = two_triangles();
  m.points.emplace_back(5, 5, 5);
  EXPECT_EQ(validation_error(m),
            "test mesh: vertex 5 is not used by any face (expected none unused)");
}

TEST(TriangleMesh, RejectsBowTieVertex) {
  // Two triangles touching only at vertex 1, and two squares (fans with interior edges) too.
  TriangleMesh m;
  m.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(-1, 0, 0),
              Point3(0, -1, 0)};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(validation_error(m),
            "test mesh: vertex 1 is non-manifold: its faces form 2 separate fans (expected one "
            "fan of faces around each vertex)");
  TriangleMesh squares = two_triangles();
  for (int i = 0; i < 3; ++i) squares.points.push_back(-squares.points[i + 1]);
  squares.triangles.push_back({0, 4, 5});
  squares.triangles.push_back({0, 5, 6});
  EXPECT_NE(validation_error(squares).find("vertex 1 is non-manifold: its faces form 2"),
            std::string::npos);
}

TEST(TriangleMesh, RejectsBadGroups) {
  TriangleMesh m = two_triangles();
  m.groups["clamped"] = {0, 4};
  EXPECT_EQ(validation_error(m),
            "test mesh: group 'clamped' refers to vertex 5 but the mesh has 4 vertices");
  m.groups["clamped"] = {1, 1};
  EXPECT_EQ(validation_error(m),
            "test mesh: group 'clamped' is not sorted and unique (expected increasing vertex "
            "indices)");
  m.groups["clamped"] = {0, 3};
  EXPECT_EQ(validation_error(m), "no error");
}

TEST(TriangleMesh, TopologyRefusesNonManifoldInput) {
  TriangleMesh m = two_triangles();
  m.triangles.push_back({0, 2, 1});
  const std::string error = mesh_error([&] { TriangleTopology t(m); });
  EXPECT_NE(error.find("TriangleTopology: edge 1-3 has more than two faces"), std::string::npos);
}

namespace {

/// Writes OBJ files into a fresh directory per test.
class TriangleObj : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("mlshell_triangle_obj_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }
  /// The reader's MeshError message for an OBJ file with this text, without its directory.
  std::string read_error(const std::string& text) const {
    const auto path = write("bad.obj", text);
    std::string m = mesh_error([&] { read_obj_triangles(path); });
    const std::string prefix = dir_.string() + "/";
    if (m.rfind(prefix, 0) == 0) m.erase(0, prefix.size());
    return m;
  }

  std::filesystem::path dir_;
};

/// Vertices 1..4 of the unit square in OBJ.
const std::string kSquare =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

}  // namespace

TEST_F(TriangleObj, ReadsVerticesFacesAndIgnoresOtherLines) {
  const auto path = write("square.obj",
                          "# a comment\n"
                          "mtllib square.mtl\n"
                          "o square\n" +
                              kSquare +
                              "vt 0 0\nvn 0 0 1\n"
                              "s off\nusemtl none\n"
                              "f 1/1/1 2/2/1 3//1\r\n"
                              "f -4 3/3 -1\n");
  const TriangleMesh m = read_obj_triangles(path);
  ASSERT_EQ(m.num_points(), 4);
  EXPECT_EQ(m.points[2], Point3(1, 1, 0));
  ASSERT_EQ(m.num_triangles(), 2);
  EXPECT_EQ(m.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_TRUE(m.groups.empty());
}

TEST_F(TriangleObj, GroupsCollectTheVerticesOfTheirFaces) {
  const auto path = write("groups.obj", kSquare +
                                            "v 2 0 0\nv 2 1 0\n"
                                            "g default\nf 1 2 3\n"
                                            "g clamped load\nf 1 3 4\n"
                                            "g\nf 2 5 6\n"
                                            "g load\nf 2 6 3\n");
  const TriangleMesh m = read_obj_triangles(path);
  EXPECT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups.at("clamped"), (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(m.groups.at("load"), (std::vector<int>{0, 1, 2, 3, 5}));
}

TEST_F(TriangleObj, RejectsUnreadableFile) {
  const auto missing = dir_ / "missing.obj";
  EXPECT_EQ(mesh_error([&] { read_obj_triangles(missing); }),
            missing.string() + ": cannot open the OBJ file");
  EXPECT_NE(mesh_error([&] { read_obj_triangles(dir_); }).find("is a directory"),
            std::string::npos);
}

TEST_F(TriangleObj, RejectsMalformedNumbers) {
  EXPECT_EQ(read_error("v 0 0 0\nv 1 0x 0\n"),
            "bad.obj:2: malformed number '0x' in vertex 'v 1 0x 0'");
  EXPECT_EQ(read_error("v 0 0\n"), "bad.obj:1: vertex 'v 0 0' has fewer than three coordinates");
  EXPECT_EQ(read_error(kSquare + "f 1 2 3.5\n"),
            "bad.obj:5: bad face entry '3.5' (expected a vertex index i, i/t, i//n or i/t/n)");
  EXPECT_NE(read_error(kSquare + "f 1 2/x 3\n").find("bad.obj:5: bad face entry '2/x'"),
            std::string::npos);
  EXPECT_NE(read_error(kSquare + "f 1 2 3/1/1/1\n").find("bad face entry"), std::string::npos);
}

TEST_F(TriangleObj, RejectsBadIndex) {
  EXPECT_EQ(read_error(kSquare + "f 1 2 5\n"),
            "bad.obj:5: face refers to vertex 5 but only 4 vertices are defined before it "
            "(expected an index from 1 to 4, or from -1 to -4)");
  EXPECT_NE(read_error(kSquare + "f 1 2 -5\n").find("bad.obj:5: face refers to vertex -5"),
            std::string::npos);
  EXPECT_NE(read_error(kSquare + "f 0 1 2\n").find("bad.obj:5: bad face entry '0'"),
            std::string::npos);
}

TEST_F(TriangleObj, RejectsQuadFace) {
  EXPECT_EQ(read_error(kSquare + "\nf 1 2 3 4\n"),
            "bad.obj:6: face with 4 vertices: mlshell's triangle shells need a triangle mesh; "
            "triangulate the face first");
}

TEST_F(TriangleObj, RejectsEmptyMesh) {
  EXPECT_EQ(read_error(kSquare), "bad.obj: the mesh has no triangles (expected at least one)");
}

TEST_F(TriangleObj, RejectsNanCoordinate) {
  EXPECT_EQ(read_error("v 0 0 0\nv 1 0 0\n# x\nv nan 1 0\nf 1 2 3\n"),
            "bad.obj:4: vertex 3 has a non-finite coordinate (nan, 1, 0); expected finite numbers");
}

TEST_F(TriangleObj, RejectsDegenerateTriangle) {
  EXPECT_EQ(read_error(kSquare + "v 2 2 0\nf 1 2 3\nf 1 3 5\n"),
            "bad.obj:7: face 2 (vertices 1 3 5) is degenerate: zero area (its vertices are "
            "collinear or coincide)");
}

TEST_F(TriangleObj, RejectsDuplicateFace) {
  EXPECT_EQ(read_error(kSquare + "f 1 2 3\nf 1 3 4\n\nf 3 4 1\n"),
            "bad.obj:8: face 3 repeats face 2 (line 6): same vertices 3 4 1 (duplicate face)");
}

TEST_F(TriangleObj, RejectsNonManifoldEdge) {
  EXPECT_EQ(read_error(kSquare + "v 0.5 0.5 1\nf 1 2 3\nf 1 3 4\nf 1 3 5\n"),
            "bad.obj:8: face 3 makes edge 1-3 non-manifold: it is shared by face 1 (line 6), "
            "face 2 (line 7) and face 3 (line 8) (expected at most two faces per edge)");
}

TEST_F(TriangleObj, RejectsFlippedFace) {
  EXPECT_EQ(read_error(kSquare + "f 1 2 3\nf 1 4 3\n"),
            "bad.obj:6: face 2 is flipped relative to face 1 (line 5): both run edge 3->1 in the "
            "same direction (expected consistently oriented faces)");
}

TEST_F(TriangleObj, RejectsUnusedVertex) {
  EXPECT_EQ(read_error(kSquare + "v 3 3 3\nf 1 2 3\nf 1 3 4\n"),
            "bad.obj:5: vertex 5 is not used by any face (expected none unused)");
}

TEST_F(TriangleObj, RejectsBowTieVertex) {
  EXPECT_EQ(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n"),
            "bad.obj:1: vertex 1 is non-manifold: its faces form 2 separate fans (expected one "
            "fan of faces around each vertex)");
}
