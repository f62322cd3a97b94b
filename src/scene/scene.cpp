// parse_scene(): loads a scene file and validates it section by section (the sections' readers
// live beside this file), plus the small pieces of scene.hpp that act on a parsed Scene.
#include "mlshell/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>

#include "scene_sections.hpp"

namespace mlshell {
namespace scene_reading {

namespace fs = std::filesystem;

std::filesystem::path read_existing_path(const Field& field, const fs::path& scene_dir) {
  const fs::path written = field.string();
  const fs::path resolved =
      (written.is_absolute() ? written : scene_dir / written).lexically_normal();
  std::error_code error;
  if (!fs::exists(resolved, error)) {
    field.fail("file not found: " + resolved.string(),
               "a path relative to the scene file's folder");
  }
  return resolved;
}

namespace {

/// Line `index` (0-based) of `content`, or "" past its end.
std::string line_of(const std::string& content, int index) {
  std::istringstream lines(content);
  std::string line;
  for (int i = 0; std::getline(lines, line); ++i) {
    if (i == index) return line;
  }
  return "";
}

/// The scene file's single YAML document; yaml-cpp's own message (with line and column) for
/// malformed YAML, and the offending line as the value.
YAML::Node load_document(const fs::path& file) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    throw SceneError(file.string() + ": cannot read the scene file: " +
                     (fs::exists(file, error) ? "not a regular file" : "no such file"));
  }
  std::ifstream in(file, std::ios::binary);
  const std::string content{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in) throw SceneError(file.string() + ": cannot read the scene file");

  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(content);
  } catch (const YAML::Exception& e) {
    throw SceneError(file.string() + ":" + std::to_string(e.mark.line + 1) + ":" +
                     std::to_string(e.mark.column + 1) + ": malformed YAML: " + e.msg + "; got '" +
                     line_of(content, e.mark.line) + "'");
  }
  if (documents.size() > 1) {
    throw SceneError(file.string() + ":" + std::to_string(documents[1].Mark().line + 1) +
                     ": a scene file holds one YAML document; got " +
                     std::to_string(documents.size()) + " (separated by '---')");
  }
  if (documents.empty() || documents.front().IsNull()) {
    throw SceneError(file.string() +
                     ":1: the scene file is empty (expected a map with keys "
                     "geometry, material, time, ...; see mlshell --help)");
  }
  return documents.front();
}

InitialState read_initial_state(const Field& field, const fs::path& scene_dir) {
  field.expect_keys({"affine", "translate", "checkpoint"});
  InitialState state;
  const std::optional<Field> checkpoint = field.find("checkpoint");
  if (checkpoint) {
    checkpoint->check(field.entries().size() == 1,
                      "a checkpoint holds the whole state; give it without affine or translate");
    state.checkpoint = read_existing_path(*checkpoint, scene_dir);
  }
  if (const auto affine = field.find("affine")) {
    const std::vector<Field> rows =
        affine->items(3, "a 3x3 matrix [[a11, a12, a13], [...], [...]]");
    std::array<Vec3, 3> matrix{};
    for (std::size_t i = 0; i < 3; ++i)
      matrix[i] = rows[i].numbers<3>("a matrix row [ai1, ai2, ai3]");
    state.affine = matrix;
  }
  if (const auto translate = field.find("translate")) {
    state.translate = translate->numbers<3>("[x, y, z] in m");
  }
  return state;
}

TimeSpec read_time(const Field& field) {
  field.expect_keys(
      {"dt", "steps", "integrator", "proximal_step", "max_proximal_solves", "preview"});
  TimeSpec time;
  time.dt = field.require("dt", "a number > 0, in s").positive_number();
  time.steps = field.require("steps", "an integer in 1..1000000").integer_in(1, 1000000);
  if (const auto integrator = field.find("integrator")) {
    const std::string kind = integrator->string();
    integrator->check(kind == "implicit_euler" || kind == "quasistatic" || kind == "progressive",
                      "unknown integrator", "implicit_euler, quasistatic or progressive");
    if (kind == "quasistatic") time.integrator = TimeSpec::Integrator::kQuasistatic;
    if (kind == "progressive") time.integrator = TimeSpec::Integrator::kProgressive;
  }
  for (const char* key : {"proximal_step", "max_proximal_solves"})
    if (const auto f = field.find(key))
      f->check(time.quasistatic(), "only a quasistatic integrator has this parameter",
               "integrator: quasistatic, or no " + std::string(key));
  if (const auto h = field.find("proximal_step")) time.proximal_step = h->positive_number();
  if (const auto n = field.find("max_proximal_solves"))
    time.max_proximal_solves = n->integer_in(1, 100000);
  if (const auto preview = field.find("preview")) {
    preview->check(time.progressive(), "only a progressive integrator has preview parameters",
                   "integrator: progressive, or no preview");
    preview->expect_keys({"max_iterations", "tolerance", "min_step", "max_steps"});
    PreviewSpec& p = time.preview;
    if (const auto f = preview->find("max_iterations")) p.max_iterations = f->integer_in(1, 1000);
    if (const auto f = preview->find("tolerance")) p.tolerance = f->positive_number();
    if (const auto f = preview->find("min_step")) {
      p.min_step = f->positive_number();
      f->check(p.min_step < 1.0, "must be below 1", "a step length in (0, 1), e.g. 1e-3");
    }
    if (const auto f = preview->find("max_steps")) p.max_steps = f->integer_in(1, 1000000);
  }
  return time;
}

bool is_probe_name(const std::string& name) {
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.';
  });
}

std::vector<Probe> read_probes(const Field& field, const GeometrySpec& geometry) {
  std::vector<Probe> probes;
  if (field.is_null()) return probes;
  // Probe names become CSV column names and JSON keys: keep them to characters safe in both.
  for (const auto& [name, where] : field.entries()) {
    if (!is_probe_name(name)) {
      throw SceneError(where.context() +
                       ": probe names may hold only letters, digits, '_', '-' "
                       "and '.'; got '" +
                       name + "'");
    }
    probes.push_back(Probe{name, read_where(where, SelectionUse::Point, "a probe", geometry)});
  }
  return probes;
}

OutputSpec read_output(const Field& field) {
  field.expect_keys({"dir", "every", "formats", "samples_per_face", "checkpoint_every"});
  OutputSpec output;
  if (const auto dir = field.find("dir")) output.dir = fs::path(dir->string()).lexically_normal();
  if (const auto every = field.find("every")) output.every = every->integer_in(1, INT_MAX);
  if (const auto formats = field.find("formats")) {
    output.formats.clear();
    for (const Field& item : formats->items()) {
      const std::string format = item.string();
      item.check(format == "xdmf" || format == "obj" || format == "csv", "unknown output format",
                 "xdmf, obj or csv");
      item.check(
          std::find(output.formats.begin(), output.formats.end(), format) == output.formats.end(),
          "format given twice");
      output.formats.push_back(format);
    }
  }
  if (const auto samples = field.find("samples_per_face")) {
    output.samples_per_face = samples->integer_in(1, 16);
  }
  if (const auto every = field.find("checkpoint_every")) {
    output.checkpoint_every = every->integer_in(0, INT_MAX);
  }
  return output;
}

SolverSpec read_solver(const Field& field, const fs::path& scene_dir) {
  field.expect_keys({"options_file"});
  SolverSpec solver;
  if (const auto options = field.find("options_file")) {
    solver.options_file = read_existing_path(*options, scene_dir);
  }
  return solver;
}

}  // namespace
}  // namespace scene_reading

Scene parse_scene(const std::filesystem::path& file) {
  using namespace scene_reading;
  const Field root = Field::document(load_document(file), file.string());
  root.expect_keys({"name", "geometry", "material", "bodies", "effects", "initial_state", "time",
                    "probes", "output", "solver"});
  const std::filesystem::path scene_dir = file.parent_path();

  Scene scene;
  scene.file = file;
  const std::optional<Field> name = root.find("name");
  scene.name = name ? name->string() : file.stem().string();
  // Geometry first, whatever the order in the file: selections are checked against the cage.
  scene.geometry = read_geometry(root.require("geometry", "{cage: {...}, refine: n}"), scene_dir);
  const Field material = root.require("material", "{model: ..., thickness, density}");
  scene.material = read_material(material);
  const bool triangle_material = std::holds_alternative<TriangleMaterial>(scene.material.model);
  if (triangle_material != scene.geometry.triangles())
    material.require("model", "")
        .fail(triangle_material
                  ? "is a triangle-mesh material, but the geometry is a subdivision cage"
                  : "is a subdivision-shell material, but the geometry is a triangle mesh",
              triangle_material ? "clyde-orthotropic or isotropic-svk, or geometry: {mesh: {...}}"
                                : "neo-hookean or st-venant-kirchhoff, or geometry: {cage: {...}}");
  if (const auto bodies = root.find("bodies"))
    scene.bodies = read_bodies(*bodies, scene, scene_dir);
  if (const auto effects = root.find("effects"))
    scene.effects = read_effects(*effects, scene.geometry, scene_dir);
  if (const auto initial = root.find("initial_state")) {
    scene.initial_state = read_initial_state(*initial, scene_dir);
  }
  scene.time = read_time(root.require("time", "{dt: ..., steps: ...}"));
  if (scene.time.quasistatic() && scene.has_inertia()) {
    const Field effects = *root.find("effects");
    effects.check(false, "a quasistatic scene has no inertia effect",
                  "no inertia (time.proximal_step sets the proximal term), or integrator: "
                  "implicit_euler");
  }
  if (scene.time.progressive()) {
    const Field integrator = root.require("time", "").require("integrator", "");
    integrator.check(scene.geometry.triangles(),
                     "a progressive run needs a triangle mesh (subdivision cages refine by RMTR)",
                     "geometry: {mesh: {...}, hierarchy: {...}}, or integrator: quasistatic");
    integrator.check(scene.geometry.hierarchy.has_value(),
                     "a progressive run needs levels to refine: the scene has no "
                     "geometry.hierarchy",
                     "geometry.hierarchy: {levels: 3, ratio: 4}, or integrator: quasistatic");
    if (scene.initial_state.checkpoint)
      root.require("initial_state", "")
          .require("checkpoint", "")
          .fail("a progressive run starts on the coarsest level, not from a checkpoint of the "
                "finest",
                "no initial_state.checkpoint, or integrator: quasistatic");
    const bool contact = std::any_of(scene.effects.begin(), scene.effects.end(), [](const Effect& e) {
      return std::holds_alternative<ContactEffect>(e);
    });
    if (contact)
      root.require("time", "")
          .require("integrator", "")
          .fail("contact in a progressive run needs safe refinement, which mlshell does not have "
                "yet (docs/contact.md)",
                "integrator: quasistatic");
  }
  if (const auto probes = root.find("probes")) scene.probes = read_probes(*probes, scene.geometry);
  if (const auto output = root.find("output")) scene.output = read_output(*output);
  if (const auto solver = root.find("solver")) scene.solver = read_solver(*solver, scene_dir);
  return scene;
}

double Motion::progress(double t) const {
  if (t <= over[0]) return 0.0;
  if (t >= over[1]) return 1.0;
  return (t - over[0]) / (over[1] - over[0]);
}

Vec3 Motion::at(double t) const {
  const double s = progress(t);
  return {s * translate[0], s * translate[1], s * translate[2]};
}

Mat3 Motion::rotation(double t) const {
  Mat3 R{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  if (!rotate) return R;
  const Vec3& a = rotate->axis;
  const double length = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const Vec3 k{a[0] / length, a[1] / length, a[2] / length};
  const double alpha = progress(t) * rotate->angle;
  const double sin_a = std::sin(alpha), one_minus_cos = 1.0 - std::cos(alpha);
  // K v = k × v; K² = k kᵀ − I.
  const Mat3 K{Vec3{0, -k[2], k[1]}, Vec3{k[2], 0, -k[0]}, Vec3{-k[1], k[0], 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      R[i][j] += sin_a * K[i][j] + one_minus_cos * (k[i] * k[j] - (i == j ? 1.0 : 0.0));
  return R;
}

double Motion::reach(double radius) const {
  double d = std::sqrt(translate[0] * translate[0] + translate[1] * translate[1] +
                       translate[2] * translate[2]);
  if (rotate) {
    const double half = 0.5 * std::abs(rotate->angle);
    d += 2.0 * radius * (half >= 0.5 * std::numbers::pi ? 1.0 : std::sin(half));
  }
  return d;
}

std::string effect_name(const Effect& e) {
  return std::string(scene_reading::kEffectNames[e.index()]);
}

bool GeometrySpec::has_frame() const {
  if (mesh) return mesh->generator == TriangleMeshSpec::Generator::kRectangle;
  return !std::holds_alternative<ObjCage>(cage);
}

bool Scene::has_inertia() const {
  return std::any_of(effects.begin(), effects.end(),
                     [](const Effect& e) { return std::holds_alternative<InertiaEffect>(e); });
}

}  // namespace mlshell
