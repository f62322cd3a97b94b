// The `geometry:` section: the cage (a generated rectangle or L-shape, or an OBJ file) and the
// number of uniform Catmull–Clark refinements.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "scene_sections.hpp"

namespace mlshell::scene_reading {
namespace {

// Generous bound that keeps every face and vertex count of a generated cage within int.
constexpr int kMaxFacesPerDirection = 100000;

std::string format_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

std::array<double, 2> read_size(const Field& field) {
  const std::vector<Field> items = field.items(2, "[width, height] in m");
  return {items[0].positive_number(), items[1].positive_number()};
}

std::array<int, 2> read_faces(const Field& field) {
  const std::vector<Field> items = field.items(2, "[nx, ny]");
  return {items[0].integer_in(1, kMaxFacesPerDirection),
          items[1].integer_in(1, kMaxFacesPerDirection)};
}

/// Why `cut` cannot be cut from a side of length `size` split into `faces` faces, or "" if it can:
/// it must lie in (0, size) and be a whole number of faces (within 1e-9), leaving at least one.
std::string cut_problem(double cut, double size, int faces) {
  const double face = size / faces;
  if (!(cut > 0.0 && cut < size)) return "must be in (0, " + format_number(size) + ")";
  const double cut_faces = cut / face;
  const double whole = std::round(cut_faces);
  if (std::abs(cut_faces - whole) > 1e-9) {
    return "must be a whole number of faces: the face size is " + format_number(face) +
           ", so the cut spans " + format_number(cut_faces) + " faces";
  }
  if (whole < 1.0 || whole > faces - 1) {
    return "must leave at least one face on each side of the cut (" + std::to_string(faces) +
           " faces of " + format_number(face) + ")";
  }
  return "";
}

LShapeCage read_l_shape(const Field& cage) {
  cage.expect_keys({"generator", "size", "faces", "cut", "origin"});
  LShapeCage l_shape;
  if (const auto size = cage.find("size")) l_shape.size = read_size(*size);
  if (const auto faces = cage.find("faces")) l_shape.faces = read_faces(*faces);
  if (const auto origin = cage.find("origin")) l_shape.origin = origin->numbers<2>("[x, y] in m");

  const std::optional<Field> cut = cage.find("cut");
  if (cut) l_shape.cut = cut->numbers<2>("[cx, cy] in m");
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string problem = cut_problem(l_shape.cut[i], l_shape.size[i], l_shape.faces[i]);
    if (problem.empty()) continue;
    if (cut) cut->items()[i].fail(problem);
    // Only the default cut is left to blame: say so, so the user knows to give one.
    cage.fail("cut[" + std::to_string(i) + "] (default " + format_number(l_shape.cut[i]) + ") " +
              problem + "; give `cut: [cx, cy]`");
  }
  return l_shape;
}

RectangleCage read_rectangle(const Field& cage) {
  cage.expect_keys({"generator", "size", "faces", "origin"});
  RectangleCage rectangle;
  if (const auto size = cage.find("size")) rectangle.size = read_size(*size);
  if (const auto faces = cage.find("faces")) rectangle.faces = read_faces(*faces);
  if (const auto origin = cage.find("origin")) rectangle.origin = origin->numbers<2>("[x, y] in m");
  return rectangle;
}

decltype(GeometrySpec::cage) read_cage(const Field& cage, const std::filesystem::path& scene_dir) {
  const std::optional<Field> obj = cage.find("obj");
  const std::optional<Field> generator = cage.find("generator");
  if (obj) {
    cage.expect_keys({"obj"});
    return ObjCage{read_existing_path(*obj, scene_dir)};
  }
  if (!generator) {
    cage.fail("a cage needs `generator` or `obj`",
              "{generator: rectangle | l-shape, ...} or {obj: path/to/cage.obj}");
  }
  const std::string kind = generator->string();
  if (kind == "rectangle") return read_rectangle(cage);
  if (kind == "l-shape") return read_l_shape(cage);
  generator->fail("unknown generator", "rectangle or l-shape");
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TriangleMeshSpec read_mesh(const Field& mesh, const std::filesystem::path& scene_dir) {
  TriangleMeshSpec spec;
  using G = TriangleMeshSpec::Generator;
  if (const auto obj = mesh.find("obj")) {
    mesh.expect_keys({"obj"});
    spec.generator = G::kObj;
    spec.obj = read_existing_path(*obj, scene_dir);
    return spec;
  }
  const std::optional<Field> generator = mesh.find("generator");
  if (!generator)
    mesh.fail("a mesh needs `generator` or `obj`",
              "{generator: rectangle | cylinder | dome | sphere, ...} or {obj: path/to/mesh.obj}");
  const std::string kind = generator->string();
  const auto positive = [&](const char* key, double& value) {
    if (const auto f = mesh.find(key)) value = f->positive_number();
  };
  if (kind == "rectangle") {
    mesh.expect_keys({"generator", "size", "faces", "edge_length", "origin", "diagonals", "relief"});
    if (const auto relief = mesh.find("relief")) {
      relief->expect_keys({"amplitude", "bumps"});
      spec.relief_amplitude = relief->require("amplitude", "a height in m, nonzero").number();
      relief->find("amplitude")->check(spec.relief_amplitude != 0.0, "must be nonzero");
      if (const auto bumps = relief->find("bumps")) {
        const std::vector<Field> n = bumps->items(2, "[nx, ny]: bumps along x and y");
        spec.relief_bumps = {n[0].integer_in(1, 10000), n[1].integer_in(1, 10000)};
      }
    }
    spec.generator = G::kRectangle;
    if (const auto d = mesh.find("diagonals")) {
      const std::string name = d->string();
      d->check(name == "alternating" || name == "uniform", "unknown diagonal pattern",
               "alternating (criss-cross, the default) or uniform (all bottom-left to top-right)");
      d->check(!mesh.find("edge_length"),
               "applies to structured rectangles (faces), not to "
               "unstructured ones (edge_length)");
      spec.uniform_diagonals = name == "uniform";
    }
    if (const auto size = mesh.find("size")) spec.size = read_size(*size);
    if (const auto faces = mesh.find("faces")) spec.faces = read_faces(*faces);
    if (const auto origin = mesh.find("origin")) spec.origin = origin->numbers<2>("[x, y] in m");
    if (const auto l = mesh.find("edge_length")) {
      l->check(!mesh.find("faces"), "give either faces (structured) or edge_length (unstructured)");
      spec.edge_length = l->positive_number();
      l->check(*spec.edge_length <= 0.5 * std::min(spec.size[0], spec.size[1]),
               "must be at most half the rectangle's shorter side");
      l->check(spec.size[0] * spec.size[1] / (*spec.edge_length * *spec.edge_length) <= 4e6,
               "gives more than ~10 million triangles");
    }
  } else if (kind == "cylinder") {
    mesh.expect_keys({"generator", "radius", "length", "faces", "imperfection"});
    spec.generator = G::kCylinder;
    spec.faces = {32, 16};
    positive("radius", spec.radius);
    positive("length", spec.length);
    if (const auto faces = mesh.find("faces")) spec.faces = read_faces(*faces);
    if (const auto faces = mesh.find("faces"))
      faces->check(spec.faces[0] >= 3, "needs at least 3 faces around", "[around >= 3, along]");
    if (const auto imperfection = mesh.find("imperfection")) {
      const std::vector<Field> modes =
          imperfection->is_sequence() ? imperfection->items() : std::vector{*imperfection};
      imperfection->check(!modes.empty(), "needs a mode",
                          "{amplitude: a, waves: [k, m], phase: p} or a list of them");
      double sum = 0.0;
      for (const Field& mode : modes) {
        mode.expect_keys({"amplitude", "waves", "phase"});
        TriangleMeshSpec::WallMode m;
        const Field a = mode.require("amplitude", "a radial offset in m, nonzero");
        m.amplitude = a.number();
        a.check(m.amplitude != 0.0, "must be nonzero");
        sum += std::abs(m.amplitude);
        if (const auto waves = mode.find("waves")) {
          const std::vector<Field> n = waves->items(2, "[k, m]: waves around and along");
          m.waves = {n[0].integer_in(0, 10000), n[1].integer_in(0, 10000)};
          waves->check(m.waves[0] > 0 || m.waves[1] > 0, "needs a wave around or along",
                       "[k, m], not both 0");
        }
        if (const auto phase = mode.find("phase")) m.phase = phase->number();
        spec.imperfection.push_back(m);
      }
      imperfection->check(sum < 0.5 * spec.radius,
                          "its amplitudes add up to half the radius or more");
    }
  } else if (kind == "dome") {
    mesh.expect_keys({"generator", "radius", "opening_angle", "rings"});
    spec.generator = G::kDome;
    positive("radius", spec.radius);
    if (const auto a = mesh.find("opening_angle")) {
      spec.opening_angle = a->positive_number();
      a->check(spec.opening_angle < kPi, "must be in (0, pi) (radians)");
    }
    if (const auto r = mesh.find("rings")) spec.rings = r->integer_in(1, 2000);
  } else if (kind == "sphere") {
    mesh.expect_keys({"generator", "radius", "subdivisions"});
    spec.generator = G::kSphere;
    positive("radius", spec.radius);
    if (const auto s = mesh.find("subdivisions")) spec.subdivisions = s->integer_in(0, 8);
  } else {
    generator->fail("unknown generator", "rectangle, cylinder, dome or sphere");
  }
  return spec;
}

namespace {

HierarchySpec read_hierarchy(const Field& hierarchy) {
  hierarchy.expect_keys({"levels", "ratio", "vertices", "boundary_deviation"});
  HierarchySpec spec;
  if (const auto deviation = hierarchy.find("boundary_deviation")) {
    spec.boundary_deviation = deviation->number();
    deviation->check(spec.boundary_deviation >= 0.0 && spec.boundary_deviation < 0.5,
                     "a coarse boundary edge may stray at most this fraction of its length from "
                     "the fine boundary",
                     "a number in [0, 0.5): 0 keeps every boundary vertex off a straight line");
  }
  if (const auto vertices = hierarchy.find("vertices")) {
    for (const char* key : {"levels", "ratio"})
      if (const auto other = hierarchy.find(key))
        other->fail("give either levels (with ratio) or vertices, not both");
    const std::vector<Field> items = vertices->items();
    vertices->check(!items.empty() && items.size() <= 11,
                    "a hierarchy needs 1 to 11 coarse levels",
                    "[n1, n2, ...]: the coarse levels' vertex counts, finest-but-one first");
    for (const Field& item : items) {
      const int n = item.integer_in(4, 1 << 30);
      item.check(spec.vertices.empty() || n < spec.vertices.back(),
                 "each coarse level must have fewer vertices than the finer one before it");
      spec.vertices.push_back(n);
    }
    spec.levels = static_cast<int>(items.size()) + 1;
    return spec;
  }
  if (const auto levels = hierarchy.find("levels")) spec.levels = levels->integer_in(2, 12);
  if (const auto ratio = hierarchy.find("ratio")) {
    spec.ratio = ratio->number();
    ratio->check(spec.ratio > 1.0 && spec.ratio <= 64.0,
                 "each level must have fewer vertices than the next finer one",
                 "a number in (1, 64]: a finer level's vertices per coarse vertex");
  }
  return spec;
}

}  // namespace

GeometrySpec read_geometry(const Field& geometry, const std::filesystem::path& scene_dir) {
  geometry.expect_keys({"cage", "refine", "mesh", "hierarchy"});
  GeometrySpec spec;
  if (const auto mesh = geometry.find("mesh")) {
    mesh->check(!geometry.find("cage"),
                "a geometry is either a subdivision cage or a triangle mesh, not both");
    if (const auto refine = geometry.find("refine"))
      refine->fail("refine applies to subdivision cages, not triangle meshes");
    spec.mesh = read_mesh(*mesh, scene_dir);
    if (const auto hierarchy = geometry.find("hierarchy")) spec.hierarchy = read_hierarchy(*hierarchy);
    return spec;
  }
  if (const auto hierarchy = geometry.find("hierarchy"))
    hierarchy->fail("hierarchy applies to triangle meshes; a subdivision cage's levels come from "
                    "refine",
                    "geometry: {mesh: {...}, hierarchy: {levels: 4, ratio: 4}}");
  spec.cage = read_cage(geometry.require("cage",
                                         "{generator: rectangle, ...} or {obj: path}, "
                                         "or a triangle mesh: {mesh: {...}}"),
                        scene_dir);
  if (const auto refine = geometry.find("refine")) spec.refine = refine->integer_in(0, 8);
  return spec;
}

}  // namespace mlshell::scene_reading
