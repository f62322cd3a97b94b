// Scene parsing: valid scenes give the expected structs (defaults, presets, paths, every where-form
// and every effect); each class of broken input gives a SceneError that names the file and line,
// the key path and the offending value. Broken scenes live in tests/data/bad/ (the CLI tests run
// them through `mlshell` too); each is a complete scene except for the one defect its comment
// names.
#include "mlshell/scene.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <numeric>
#include <sstream>

namespace mlshell {
namespace {

namespace fs = std::filesystem;

const fs::path kData = MLSHELL_TEST_DATA;

Scene parse_fixture(const std::string& name) { return parse_scene(kData / "scenes" / name); }

/// A folder of its own under the system's temporary folder, removed at the end of the test.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("mlshell_scene_test_" + std::to_string(::getpid()) + "_" + test->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() { fs::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  fs::path write(const std::string& name, const std::string& content) const {
    const fs::path file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << content;
    return file;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

constexpr const char* kTriangleMaterial =
    "material: {model: neo-hookean, youngs_modulus: 1.0e6, poisson_ratio: 0.3, thickness: 0.001, "
    "volume_density: 500}\n";

/// The parts of a small valid scene, to be replaced one at a time by a test.
struct SceneText {
  std::string geometry = "geometry: {cage: {generator: rectangle, faces: [4, 4]}}\n";
  std::string material =
      "material: {model: isotropic-svk, youngs_modulus: 1e7, poisson_ratio: 0.3, "
      "thickness: 1e-3, density: 1}\n";
  std::string effects = "effects: [inertia, gravity]\n";
  std::string time = "time: {dt: 1.0, steps: 2}\n";
  std::string extra;
  std::string str() const { return geometry + material + effects + time + extra; }
};

/// The message of the SceneError that parsing `file` throws ("" and a test failure if none).
std::string scene_error(const fs::path& file) {
  try {
    parse_scene(file);
  } catch (const SceneError& error) {
    return error.what();
  }
  ADD_FAILURE() << file << " parsed without error";
  return {};
}

/// Expects parsing `file` to fail with a message that starts with `<file>:<line>` and contains
/// every fragment (the key path, the offending value, the problem).
void expect_scene_error(const fs::path& file, int line, const std::vector<std::string>& fragments) {
  const std::string message = scene_error(file);
  const std::string location = file.string() + ":" + std::to_string(line) + ":";
  EXPECT_EQ(message.rfind(location, 0), 0u) << "expected it to start with " << location << "\n"
                                            << message;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(message.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n"
                                                         << message;
  }
}

void expect_bad_fixture(const std::string& name, int line,
                        const std::vector<std::string>& fragments) {
  SCOPED_TRACE(name);
  expect_scene_error(kData / "bad" / name, line, fragments);
}

void expect_vec3(const Vec3& actual, const Vec3& expected) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(actual[i], expected[i]) << "component " << i;
}

template <class T, class Variant>
const T& as(const Variant& v) {
  EXPECT_TRUE(std::holds_alternative<T>(v));
  return std::get<T>(v);
}

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST(SceneParse, MinimalSceneTakesEveryDefault) {
  const Scene scene = parse_fixture("minimal_svk.yaml");
  EXPECT_EQ(scene.name, "minimal_svk");
  EXPECT_EQ(scene.file, kData / "scenes" / "minimal_svk.yaml");

  const auto& cage = as<RectangleCage>(scene.geometry.cage);
  EXPECT_EQ(cage.size, (std::array<double, 2>{1.0, 1.0}));
  EXPECT_EQ(cage.faces, (std::array<int, 2>{4, 4}));
  EXPECT_EQ(cage.origin, (std::array<double, 2>{0.0, 0.0}));
  EXPECT_EQ(scene.geometry.refine, 0);

  const auto& svk = as<SvkMaterial>(scene.material.model);
  EXPECT_DOUBLE_EQ(svk.youngs_modulus, 1e7);
  EXPECT_DOUBLE_EQ(svk.poisson_ratio, 0.3);
  EXPECT_TRUE(scene.material.preset.empty());
  EXPECT_DOUBLE_EQ(scene.material.thickness, 1e-3);
  EXPECT_DOUBLE_EQ(scene.material.density, 1.0);
  expect_vec3(scene.material.warp, {1, 0, 0});
  EXPECT_EQ(scene.material.thickness_points, 3);

  EXPECT_TRUE(scene.effects.empty());
  EXPECT_FALSE(scene.has_inertia());
  EXPECT_FALSE(scene.initial_state.affine);
  EXPECT_FALSE(scene.initial_state.checkpoint);
  expect_vec3(scene.initial_state.translate, {0, 0, 0});
  EXPECT_DOUBLE_EQ(scene.time.dt, 1.0);
  EXPECT_EQ(scene.time.steps, 1);
  EXPECT_TRUE(scene.probes.empty());
  EXPECT_EQ(scene.output.dir, fs::path("out"));
  EXPECT_EQ(scene.output.every, 1);
  EXPECT_EQ(scene.output.formats, (std::vector<std::string>{"xdmf", "obj", "csv"}));
  EXPECT_EQ(scene.output.samples_per_face, 0);  // automatic: fewer per face on finer levels
  EXPECT_EQ(scene.output.samples_for(0), 4);
  EXPECT_EQ(scene.output.samples_for(2), 4);
  EXPECT_EQ(scene.output.samples_for(3), 2);
  EXPECT_EQ(scene.output.samples_for(4), 1);
  EXPECT_EQ(scene.output.samples_for(8), 1);
  EXPECT_EQ(scene.output.checkpoint_every, 0);
  EXPECT_FALSE(scene.solver.options_file);
}

TEST(SceneParse, FullRectangleSceneReadsEverySection) {
  const Scene scene = parse_fixture("full_rectangle.yaml");
  EXPECT_EQ(scene.name, "full-rectangle");

  const auto& cage = as<RectangleCage>(scene.geometry.cage);
  EXPECT_EQ(cage.size, (std::array<double, 2>{2.0, 1.0}));
  EXPECT_EQ(cage.faces, (std::array<int, 2>{8, 4}));
  EXPECT_EQ(cage.origin, (std::array<double, 2>{-1.0, 0.0}));
  EXPECT_EQ(scene.geometry.refine, 2);

  EXPECT_EQ(scene.material.preset, "denim");
  const auto& clyde = as<ClydeMaterial>(scene.material.model);
  EXPECT_EQ(clyde.k, denim_preset().k);
  EXPECT_DOUBLE_EQ(scene.material.thickness, 0.5e-3);  // given values win over the preset's
  EXPECT_DOUBLE_EQ(scene.material.density, 0.3);
  expect_vec3(scene.material.warp, {0, 1, 0});
  EXPECT_EQ(scene.material.thickness_points, 4);

  ASSERT_EQ(scene.effects.size(), 8u);
  std::vector<std::string> names;
  for (const Effect& e : scene.effects) names.push_back(effect_name(e));
  EXPECT_EQ(names, (std::vector<std::string>{"inertia", "gravity", "surface_load", "line_load",
                                             "point_load", "dirichlet", "dirichlet", "clamp"}));
  EXPECT_TRUE(scene.has_inertia());

  expect_vec3(as<GravityEffect>(scene.effects[1]).acceleration, {0, 0, -9.81});

  const auto& surface = as<SurfaceLoadEffect>(scene.effects[2]);
  expect_vec3(surface.force_per_area, {0, 0, -90});
  EXPECT_TRUE(surface.ramp);

  const auto& line = as<LineLoadEffect>(scene.effects[3]);
  EXPECT_EQ(line.where.text, "boundary(right)");
  const auto& right = as<CurveSelection>(line.where.selection);
  EXPECT_EQ(right.kind, CurveSelection::Kind::Side);
  EXPECT_EQ(right.side, "right");
  expect_vec3(line.force_per_length, {0, 0, -4});
  EXPECT_TRUE(line.ramp);

  const auto& point = as<PointLoadEffect>(scene.effects[4]);
  EXPECT_EQ(point.where.text, "at(0.5, 0.5, 0)");
  const auto& at = as<PointSelection>(point.where.selection);
  EXPECT_EQ(at.kind, PointSelection::Kind::At);
  expect_vec3(at.at, {0.5, 0.5, 0});
  expect_vec3(point.force, {0, 0, -1});
  EXPECT_FALSE(point.ramp);

  const auto& moving = as<DirichletEffect>(scene.effects[5]);
  EXPECT_EQ(moving.components, (std::array<bool, 3>{true, false, true}));
  EXPECT_DOUBLE_EQ(moving.sigma, 4.0);
  EXPECT_FALSE(moving.penalty);
  ASSERT_TRUE(moving.motion);
  expect_vec3(moving.motion->translate, {0.2, 0, 0});
  EXPECT_EQ(moving.motion->over, (std::array<double, 2>{0.0, 10.0}));

  const auto& pinned = as<DirichletEffect>(scene.effects[6]);
  EXPECT_EQ(as<PointSelection>(pinned.where.selection).corner, "top-right");
  EXPECT_EQ(pinned.components, (std::array<bool, 3>{true, true, true}));
  EXPECT_DOUBLE_EQ(pinned.sigma, 5.0);
  EXPECT_EQ(pinned.penalty, 1e8);
  EXPECT_FALSE(pinned.motion);

  const auto& clamp = as<ClampEffect>(scene.effects[7]);
  EXPECT_EQ(as<CurveSelection>(clamp.where.selection).side, "bottom");
  EXPECT_EQ(clamp.rotation_penalty, 1e3);
  EXPECT_FALSE(clamp.penalty);

  ASSERT_TRUE(scene.initial_state.affine);
  expect_vec3((*scene.initial_state.affine)[0], {1.1, 0, 0});
  expect_vec3((*scene.initial_state.affine)[2], {0, 0, 1});
  expect_vec3(scene.initial_state.translate, {0, 0, 0.1});

  EXPECT_DOUBLE_EQ(scene.time.dt, 0.5);
  EXPECT_EQ(scene.time.steps, 20);

  ASSERT_EQ(scene.probes.size(), 3u);  // in file order
  EXPECT_EQ(scene.probes[0].name, "center");
  EXPECT_EQ(scene.probes[1].name, "corner");
  EXPECT_EQ(as<PointSelection>(scene.probes[1].where.selection).corner, "bottom-left");
  EXPECT_EQ(scene.probes[2].name, "mid_left");
  const auto& param = as<PointSelection>(scene.probes[2].where.selection);
  EXPECT_EQ(param.kind, PointSelection::Kind::Param);
  EXPECT_EQ(param.param, (std::array<double, 2>{0.0, 0.5}));

  EXPECT_EQ(scene.output.dir, fs::path("out/scene-test-full"));  // relative to the working dir
  EXPECT_EQ(scene.output.every, 2);
  EXPECT_EQ(scene.output.formats, (std::vector<std::string>{"xdmf", "csv"}));
  EXPECT_EQ(scene.output.samples_per_face, 3);
  EXPECT_EQ(scene.output.samples_for(6), 3);  // given: at every refinement
  EXPECT_EQ(scene.output.checkpoint_every, 5);

  ASSERT_TRUE(scene.solver.options_file);
  EXPECT_EQ(*scene.solver.options_file, kData / "scenes" / "options.rc");
}

TEST(SceneParse, ObjCageResolvesItsPathAndTakesSpatialSelections) {
  const Scene scene = parse_fixture("obj_cage.yaml");
  const auto& cage = as<ObjCage>(scene.geometry.cage);
  EXPECT_EQ(cage.path, kData / "meshes" / "square_4x4.obj");
  EXPECT_TRUE(fs::is_regular_file(cage.path));
  EXPECT_EQ(scene.geometry.refine, 1);

  // preset: denim without thickness or density takes Table 1's.
  EXPECT_EQ(scene.material.preset, "denim");
  EXPECT_DOUBLE_EQ(scene.material.thickness, 0.66e-3);
  EXPECT_DOUBLE_EQ(scene.material.density, 0.4);

  ASSERT_EQ(scene.effects.size(), 4u);
  expect_vec3(as<GravityEffect>(scene.effects[0]).acceleration, {0, 0, -9.81});  // bare `gravity`
  const auto& clamp = as<ClampEffect>(scene.effects[1]);
  const auto& box = as<CurveSelection>(clamp.where.selection);
  EXPECT_EQ(box.kind, CurveSelection::Kind::Box);
  expect_vec3(box.box_min, {-0.01, -0.01, -0.01});
  expect_vec3(box.box_max, {1.01, 0.01, 0.01});
  EXPECT_EQ(clamp.where.text, "box([-0.01, -0.01, -0.01], [1.01, 0.01, 0.01])");

  const auto& dirichlet = as<DirichletEffect>(scene.effects[2]);
  EXPECT_EQ(as<CurveSelection>(dirichlet.where.selection).kind, CurveSelection::Kind::All);
  EXPECT_EQ(dirichlet.where.text, "boundary");
  EXPECT_EQ(dirichlet.components, (std::array<bool, 3>{false, false, true}));

  ASSERT_EQ(scene.probes.size(), 1u);
  EXPECT_EQ(scene.probes[0].where.text, "at(1, 1, 0)");
  EXPECT_EQ(scene.output.formats, (std::vector<std::string>{"obj"}));
}

TEST(SceneParse, LShapeSceneTakesReEntrantCornersAndParameters) {
  const Scene scene = parse_fixture("l_shape.yaml");
  const auto& cage = as<LShapeCage>(scene.geometry.cage);
  EXPECT_EQ(cage.faces, (std::array<int, 2>{10, 10}));
  EXPECT_EQ(cage.cut, (std::array<double, 2>{0.3, 0.3}));

  const auto& clamp = as<ClampEffect>(scene.effects[2]);
  EXPECT_EQ(as<CurveSelection>(clamp.where.selection).side, "re-entrant");
  const auto& dirichlet = as<DirichletEffect>(scene.effects[3]);
  EXPECT_EQ(as<PointSelection>(dirichlet.where.selection).param,
            (std::array<double, 2>{0.25, 0.9}));
  EXPECT_EQ(dirichlet.where.text, "point(0.25, 0.9)");
  EXPECT_EQ(dirichlet.components, (std::array<bool, 3>{true, true, false}));
  EXPECT_EQ(scene.name, "l_shape");
}

TEST(SceneParse, PathsAreRelativeToTheSceneFolderEvenForARelativeScenePath) {
  const fs::path relative_scene = fs::relative(kData / "scenes" / "obj_cage.yaml");
  ASSERT_TRUE(relative_scene.is_relative());
  const Scene scene = parse_scene(relative_scene);
  const fs::path cage = as<ObjCage>(scene.geometry.cage).path;
  EXPECT_TRUE(fs::is_regular_file(cage)) << cage;
  EXPECT_TRUE(fs::equivalent(cage, kData / "meshes" / "square_4x4.obj"));
  EXPECT_EQ(scene.output.dir, fs::path("out/scene-test-obj"));  // not moved to the scene folder
}

TEST(SceneParse, CheckpointAndOptionsFileAreResolvedNextToTheScene) {
  ScratchDir dir;
  dir.write("restart/state.h5", "");
  dir.write("options/tr.yaml", "");
  SceneText text;
  text.extra =
      "initial_state: {checkpoint: restart/state.h5}\n"
      "solver: {options_file: options/tr.yaml}\n"
      "name: from-name-key\n";
  const Scene scene = parse_scene(dir.write("nested/../scene.yaml", text.str()));
  EXPECT_EQ(scene.initial_state.checkpoint, dir.path() / "restart" / "state.h5");
  EXPECT_EQ(scene.solver.options_file, dir.path() / "options" / "tr.yaml");
  EXPECT_EQ(scene.name, "from-name-key");
}

TEST(SceneParse, ExplicitClydeParametersOverrideThePreset) {
  ScratchDir dir;
  SceneText text;
  text.material =
      "material:\n"
      "  model: clyde-orthotropic\n"
      "  preset: denim\n"
      "  k: [1e6, 2e6, 3e6, 4e6]\n"
      "  mu: [[-4617.79, -1482.1, 276.43, 2407.67, 3416.79], [0.5, 0.5], [1], [1, 0, 0]]\n"
      "  alpha: [[-7.80, 10.80, 18.95, -12.89, 1.61], [1, 2], [3], [2.95, -2823.9, 4.29]]\n";
  const Scene scene = parse_scene(dir.write("clyde.yaml", text.str()));
  const auto& clyde = as<ClydeMaterial>(scene.material.model);
  EXPECT_EQ(clyde.k, (std::array<double, 4>{1e6, 2e6, 3e6, 4e6}));
  EXPECT_EQ(clyde.mu[1], (std::vector<double>{0.5, 0.5}));
  EXPECT_EQ(clyde.alpha[2], (std::vector<double>{3}));
  EXPECT_DOUBLE_EQ(scene.material.thickness, 0.66e-3);

  // Without a preset, k, mu and alpha are all given; thickness and density are then required.
  text.material =
      "material: {model: clyde-orthotropic, k: [1, 2, 3, 4], mu: [[1], [1], [1], [1]],\n"
      "           alpha: [[2], [2], [2], [2]], thickness: 1e-3, density: 0}\n";
  const Scene plain = parse_scene(dir.write("plain.yaml", text.str()));
  EXPECT_TRUE(plain.material.preset.empty());
  EXPECT_EQ(as<ClydeMaterial>(plain.material.model).alpha[3], (std::vector<double>{2}));
  EXPECT_DOUBLE_EQ(plain.material.density, 0.0);
}

TEST(SceneParse, TriangleHierarchyByRatioOrByVertexCounts) {
  const ScratchDir dir;
  SceneText text;
  text.material = kTriangleMaterial;
  text.effects = "effects: [gravity]\n";
  text.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {levels: 3, ratio: 3.5}}\n";
  const Scene by_ratio = parse_scene(dir.write("ratio.yaml", text.str()));
  ASSERT_TRUE(by_ratio.geometry.hierarchy.has_value());
  EXPECT_EQ(by_ratio.geometry.hierarchy->levels, 3);
  EXPECT_EQ(by_ratio.geometry.hierarchy->ratio, 3.5);
  EXPECT_TRUE(by_ratio.geometry.hierarchy->vertices.empty());
  text.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {}}\n";
  const Scene defaults = parse_scene(dir.write("defaults.yaml", text.str()));
  EXPECT_EQ(defaults.geometry.hierarchy->levels, 4);
  EXPECT_EQ(defaults.geometry.hierarchy->ratio, 4.0);
  text.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {vertices: [300, 80]}}\n";
  const Scene counts = parse_scene(dir.write("counts.yaml", text.str()));
  EXPECT_EQ(counts.geometry.hierarchy->levels, 3);
  EXPECT_EQ(counts.geometry.hierarchy->vertices, (std::vector<int>{300, 80}));
  text.geometry = "geometry: {mesh: {generator: sphere}}\n";
  EXPECT_FALSE(parse_scene(dir.write("none.yaml", text.str())).geometry.hierarchy.has_value());
}

TEST(SceneParse, EffectsMayBeEmptyOrAbsent) {
  ScratchDir dir;
  SceneText text;
  text.effects = "effects: []\n";
  EXPECT_TRUE(parse_scene(dir.write("empty_list.yaml", text.str())).effects.empty());
  text.effects = "effects:\n";
  EXPECT_TRUE(parse_scene(dir.write("null.yaml", text.str())).effects.empty());
}

TEST(SceneParse, MotionsRotateTranslateOrBoth) {
  ScratchDir dir;
  SceneText text;
  text.effects =
      "effects:\n"
      "  - clamp: {where: boundary(left), motion: {rotate: {axis: [1, 0, 0], center: [0, 0.5, 0], "
      "angle: 1.5707963267948966}, over: [0, 2]}}\n"
      "  - dirichlet:\n      where: boundary(right)\n      motion:\n        translate: [0, 0, "
      "0.1]\n"
      "        rotate: {axis: [0, 0, 2], center: [1, 0, 0], angle: -0.5}\n        over: [1, 3]\n"
      "  - dirichlet: {where: boundary(top), motion: {translate: [0.1, 0, 0], over: [0, 1]}}\n";
  const Scene scene = parse_scene(dir.write("motions.yaml", text.str()));
  ASSERT_EQ(scene.effects.size(), 3u);
  // rotate alone: no translation.
  const auto& turned = *as<ClampEffect>(scene.effects[0]).motion;
  expect_vec3(turned.translate, {0, 0, 0});
  ASSERT_TRUE(turned.rotate);
  expect_vec3(turned.rotate->axis, {1, 0, 0});
  expect_vec3(turned.rotate->center, {0, 0.5, 0});
  EXPECT_DOUBLE_EQ(turned.rotate->angle, std::numbers::pi / 2);
  // Both: the axis as written (normalised only when the rotation is formed).
  const auto& both = *as<DirichletEffect>(scene.effects[1]).motion;
  expect_vec3(both.translate, {0, 0, 0.1});
  ASSERT_TRUE(both.rotate);
  expect_vec3(both.rotate->axis, {0, 0, 2});
  expect_vec3(both.rotate->center, {1, 0, 0});
  EXPECT_DOUBLE_EQ(both.rotate->angle, -0.5);
  EXPECT_EQ(both.over, (std::array<double, 2>{1.0, 3.0}));
  // translate alone: no rotation, as before.
  EXPECT_FALSE(as<DirichletEffect>(scene.effects[2]).motion->rotate);
}

TEST(SceneParse, BlockStyleWhereTakesPointWithoutQuotes) {
  ScratchDir dir;
  SceneText text;
  text.effects =
      "effects:\n"
      "  - point_load:\n"
      "      where: point(0.5, 1)\n"
      "      force: [0, 0, 1]\n";
  const Scene scene = parse_scene(dir.write("block.yaml", text.str()));
  const auto& load = as<PointLoadEffect>(scene.effects[0]);
  EXPECT_EQ(as<PointSelection>(load.where.selection).param, (std::array<double, 2>{0.5, 1.0}));
}

// ---------------------------------------------------------------------------------------------
// Pieces of scene.hpp

TEST(DenimPreset, MatchesTableOneInSiUnits) {
  const ClydeMaterial denim = denim_preset();
  EXPECT_EQ(denim.k, (std::array<double, 4>{4.79e6, 4.52e6, 9.03e6, 2.44e6}));
  const std::array<std::size_t, 4> d{5, 1, 5, 3};
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(denim.mu[j].size(), d[j]) << "j = " << j + 1;
    EXPECT_EQ(denim.alpha[j].size(), d[j]) << "j = " << j + 1;
  }
  EXPECT_DOUBLE_EQ(denim.mu[0][1], -1482.1);
  EXPECT_DOUBLE_EQ(denim.mu[2][4], 146.98);
  EXPECT_DOUBLE_EQ(denim.alpha[2][1], -12802.0);
  EXPECT_DOUBLE_EQ(denim.alpha[3][1], -2823.9);
  EXPECT_DOUBLE_EQ(denim.alpha[1][0], 1.0);
}

TEST(DenimPreset, EachPhiHasUnitSlopeAtZero) {
  // phi_j'(0) = sum_i mu_ji * alpha_ji / alpha_ji = sum_i mu_ji must be 1 (mu_j1 was completed so).
  const ClydeMaterial denim = denim_preset();
  for (std::size_t j = 0; j < 4; ++j) {
    const double sum = std::accumulate(denim.mu[j].begin(), denim.mu[j].end(), 0.0);
    EXPECT_NEAR(sum, 1.0, 1e-9) << "j = " << j + 1;
  }
}

TEST(Motion, GrowsLinearlyOverItsIntervalAndStays) {
  const Motion motion{{0.2, -0.4, 0.0}, {1.0, 3.0}};
  expect_vec3(motion.at(0.0), {0, 0, 0});
  expect_vec3(motion.at(1.0), {0, 0, 0});
  expect_vec3(motion.at(2.0), {0.1, -0.2, 0});
  expect_vec3(motion.at(3.0), {0.2, -0.4, 0});
  expect_vec3(motion.at(100.0), {0.2, -0.4, 0});
}

TEST(Motion, EqualEndsMakeAJump) {
  const Motion jump{{1, 2, 3}, {2.0, 2.0}};
  expect_vec3(jump.at(2.0), {0, 0, 0});
  expect_vec3(jump.at(2.0 + 1e-12), {1, 2, 3});
  EXPECT_FALSE(std::isnan(jump.at(2.0)[0]));
}

TEST(EffectName, NamesEveryEffect) {
  EXPECT_EQ(effect_name(InertiaEffect{}), "inertia");
  EXPECT_EQ(effect_name(GravityEffect{}), "gravity");
  EXPECT_EQ(effect_name(SurfaceLoadEffect{}), "surface_load");
  EXPECT_EQ(effect_name(LineLoadEffect{}), "line_load");
  EXPECT_EQ(effect_name(PointLoadEffect{}), "point_load");
  EXPECT_EQ(effect_name(DirichletEffect{}), "dirichlet");
  EXPECT_EQ(effect_name(ClampEffect{}), "clamp");
}

TEST(WhereText, ParsesEveryStringForm) {
  const Where all = parse_where_text(" boundary ", "ctx");
  EXPECT_EQ(as<CurveSelection>(all.selection).kind, CurveSelection::Kind::All);
  EXPECT_EQ(all.text, "boundary");

  for (const std::string side : {"left", "right", "bottom", "top", "re-entrant"}) {
    const Where w = parse_where_text("boundary(" + side + ")", "ctx");
    EXPECT_EQ(as<CurveSelection>(w.selection).kind, CurveSelection::Kind::Side);
    EXPECT_EQ(as<CurveSelection>(w.selection).side, side);
  }
  for (const std::string corner : {"bottom-left", "bottom-right", "top-left", "top-right"}) {
    const Where w = parse_where_text("corner( " + corner + " )", "ctx");
    EXPECT_EQ(as<PointSelection>(w.selection).kind, PointSelection::Kind::Corner);
    EXPECT_EQ(as<PointSelection>(w.selection).corner, corner);
  }
  const Where param = parse_where_text("point(1, 2.5e-1)", "ctx");
  EXPECT_EQ(as<PointSelection>(param.selection).param, (std::array<double, 2>{1.0, 0.25}));
}

TEST(WhereText, RejectsMalformedFormsWithTheContext) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"boundary(middle)", "unknown side"},
      {"corner(top)", "unknown corner"},
      {"corner", "unknown selection"},
      {"point(0.5)", "two numbers"},
      {"point(0.5, 1.5)", "v must be in [0, 1]"},
      {"point(nan, 0)", "NaN"},
      {"point(0.5, 0.5", "unbalanced"},
      {"edge(left)", "unknown selection"},
      {"point(a, 0)", "'a' is not a number"},
      {"", "unknown selection"}};
  for (const auto& [text, problem] : cases) {
    try {
      parse_where_text(text, "s.yaml:3: effects[0].clamp.where");
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("s.yaml:3: effects[0].clamp.where: ", 0), 0u) << message;
      EXPECT_NE(message.find(problem), std::string::npos) << message;
      EXPECT_NE(message.find("got '" + text + "'"), std::string::npos) << message;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Broken scenes: one test per class of defect, on the fixtures in tests/data/bad/.

TEST(SceneErrors, MalformedYamlReportsLineColumnAndTheLine) {
  expect_bad_fixture(
      "malformed.yaml", 3,
      {":3:62: malformed YAML: illegal flow end", "size: [1.0, 1.0, faces: [4, 4]}"});
}

TEST(SceneErrors, UnknownTopLevelKeyListsTheAllowedOnes) {
  expect_bad_fixture("unknown_top_level_key.yaml", 13,
                     {"solvers: unknown key; got 'solvers'", "allowed keys: name, geometry",
                      "did you mean 'solver'?"});
}

TEST(SceneErrors, UnknownNestedKeyListsTheAllowedOnes) {
  expect_bad_fixture("unknown_nested_key.yaml", 5,
                     {"material.thicknes: unknown key", "got 'thicknes'",
                      "allowed keys: model, youngs_modulus", "did you mean 'thickness'?"});
}

TEST(SceneErrors, UnknownEffectListsTheKnownOnes) {
  expect_bad_fixture("unknown_effect.yaml", 9,
                     {"effects[1]: unknown effect 'wind'", "got '{wind: [1, 0, 0]}'",
                      "inertia, gravity, surface_load, line_load, point_load, dirichlet, clamp"});
}

TEST(SceneErrors, NegativeThickness) {
  expect_bad_fixture("negative_thickness.yaml", 6,
                     {"material.thickness: must be > 0; got '-0.001'"});
}

TEST(SceneErrors, WrongTypeWordForAnInteger) {
  expect_bad_fixture("wrong_type.yaml", 11,
                     {"time.steps: must be a number; got 'ten'", "an integer in 1..1000000"});
}

TEST(SceneErrors, VectorOfWrongLength) {
  expect_bad_fixture(
      "wrong_vector_length.yaml", 9,
      {"effects[1].gravity: must have exactly 3 entries, has 2", "got '[0, -9.81]'"});
}

TEST(SceneErrors, MissingRequiredKey) {
  expect_bad_fixture("missing_required_key.yaml", 11,
                     {"time.dt: required key is missing", "got '{steps: 2}'", "a number > 0"});
}

TEST(SceneErrors, MissingObjFileNamesKeyAndResolvedPath) {
  const fs::path resolved = (kData / "meshes" / "no_such_cage.obj").lexically_normal();
  expect_bad_fixture("missing_obj.yaml", 3,
                     {"geometry.cage.obj: file not found: " + resolved.string(),
                      "got '../meshes/no_such_cage.obj'"});
}

TEST(SceneErrors, MissingOptionsFileAndCheckpoint) {
  expect_bad_fixture(
      "missing_options_file.yaml", 13,
      {"solver.options_file: file not found: " + (kData / "bad" / "no-such-options.yaml").string(),
       "got 'no-such-options.yaml'"});
  expect_bad_fixture("missing_checkpoint.yaml", 13,
                     {"initial_state.checkpoint: file not found: " +
                          (kData / "bad" / "checkpoints" / "none.h5").string(),
                      "got 'checkpoints/none.h5'"});
}

TEST(SceneErrors, CurveOnlyEffectGivenAPoint) {
  expect_bad_fixture("curve_effect_given_point.yaml", 10,
                     {"effects[2].line_load.where: line_load needs a curve selection",
                      "got '{at: [1, 0.5, 0]}'", "{box: {min:"});
}

TEST(SceneErrors, ProbeGivenACurve) {
  expect_bad_fixture("probe_on_curve.yaml", 13,
                     {"probes.edge: a probe needs a point selection", "got 'boundary(right)'"});
}

TEST(SceneErrors, NamedSideWithAnObjCage) {
  expect_bad_fixture("named_side_with_obj_cage.yaml", 10,
                     {"effects[2].clamp.where: named sides", "got 'boundary(left)'",
                      "with an OBJ cage, {at: [x, y, z]} or {box:"});
}

TEST(SceneErrors, ReEntrantSideOnARectangle) {
  expect_bad_fixture("re_entrant_on_rectangle.yaml", 10,
                     {"effects[2].clamp.where: boundary(re-entrant) exists only on an l-shape cage",
                      "got 'boundary(re-entrant)'"});
}

TEST(SceneErrors, NanIsNeverAccepted) {
  expect_bad_fixture("nan_value.yaml", 6,
                     {"material.density: must be a finite number", "got '.nan'"});
}

TEST(SceneErrors, LShapeCutNotAWholeNumberOfFaces) {
  expect_bad_fixture("bad_l_shape_cut.yaml", 3,
                     {"geometry.cage.cut[1]: must be a whole number of faces", "got '0.33'"});
}

TEST(SceneErrors, DuplicateInertia) {
  expect_bad_fixture(
      "duplicate_inertia.yaml", 11,
      {"effects[3]: inertia may appear only once (first given at line 8)", "got 'inertia'"});
}

TEST(SceneErrors, DuplicateKey) {
  expect_bad_fixture("duplicate_key.yaml", 13,
                     {"time: key given twice (first at line 11)", "got '{dt: 0.5, steps: 4}'"});
}

TEST(SceneErrors, OutOfRangeValues) {
  expect_bad_fixture("refine_out_of_range.yaml", 4, {"geometry.refine: must be in 0..8; got '9'"});
  expect_bad_fixture("poisson_ratio_out_of_range.yaml", 5,
                     {"material.poisson_ratio: must be in (-1, 0.5); got '0.5'"});
  expect_bad_fixture("motion_backwards.yaml", 10,
                     {"effects[2].clamp.motion.over: t0 must be <= t1; got '[10, 2]'"});
}

TEST(SceneErrors, RotationWithAZeroAxisOrAnUnknownKey) {
  expect_bad_fixture("motion_rotate_zero_axis.yaml", 12,
                     {"effects[2].clamp.motion.rotate.axis: the axis must be a non-zero vector",
                      "got '[0, 0, 0]'", "expected a direction such as [1, 0, 0]"});
  expect_bad_fixture("motion_rotate_unknown_key.yaml", 11,
                     {"effects[1].dirichlet.motion.rotate.degrees: angles are given in radians, "
                      "under `angle`; got '90'"});
}

TEST(SceneErrors, BadListEntries) {
  expect_bad_fixture("repeated_component.yaml", 10,
                     {"effects[2].dirichlet.components[2]: component given twice; got 'x'"});
  expect_bad_fixture("unknown_output_format.yaml", 12,
                     {"output.formats[1]: unknown output format; got 'vtk'", "xdmf, obj or csv"});
}

TEST(SceneErrors, EffectItemWithTwoNames) {
  expect_bad_fixture("effect_not_single_key.yaml", 9,
                     {"effects[1]: an effect is a name or a single-key map",
                      "got '{gravity: [0, 0, -9.81], clamp: {where: boundary(left)}}'"});
}

TEST(SceneErrors, ClydeWithoutPresetNeedsEveryParameter) {
  expect_bad_fixture("clyde_without_preset_missing_mu.yaml", 5,
                     {"material.mu: required key is missing", "model: clyde-orthotropic"});
}

TEST(SceneErrors, EveryBadFixtureIsRejected) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kData / "bad")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string message = scene_error(entry.path());
    EXPECT_EQ(message.rfind(entry.path().string() + ":", 0), 0u) << message;
    ++count;
  }
  EXPECT_GE(count, 14);
}

// Triangle-shell keys name the key, the value and what is allowed.
TEST(SceneErrors, TriangleBendingAndDiagonals) {
  const std::string bending = scene_error(kData / "bad" / "triangle_unknown_bending.yaml");
  EXPECT_NE(bending.find("material.bending: unknown bending model; got 'kirchhoff'"),
            std::string::npos)
      << bending;
  EXPECT_NE(bending.find("hinge"), std::string::npos) << bending;
  EXPECT_NE(bending.find("midedge"), std::string::npos) << bending;
  const std::string diagonals = scene_error(kData / "bad" / "triangle_diagonals_unstructured.yaml");
  EXPECT_NE(diagonals.find("geometry.mesh.diagonals: applies to structured rectangles"),
            std::string::npos)
      << diagonals;
}

/// Defects that need no fixture of their own: each case replaces one part of a valid scene.
TEST(SceneErrors, InlineDefects) {
  struct Case {
    std::string name;
    SceneText text;
    int line;
    std::vector<std::string> fragments;
  };
  auto with = [](auto change) {
    SceneText text;
    change(text);
    return text;
  };
  // A triangle-mesh scene without effects (for the bodies' cases).
  const auto triangle_mesh = [](SceneText& t) {
    t.geometry = "geometry: {mesh: {generator: rectangle}}\n";
    t.material = "material: {model: neo-hookean, youngs_modulus: 1e6, poisson_ratio: 0.3, "
                 "thickness: 1e-3, volume_density: 1}\n";
    t.effects = "";
  };
  const std::vector<Case> cases{
      {"quoted_number",
       with([](SceneText& t) { t.time = "time: {dt: \"1.0\", steps: 2}\n"; }),
       4,
       {"time.dt: must be a number, not a quoted string; got '1.0'"}},
      {"fractional_steps",
       with([](SceneText& t) { t.time = "time: {dt: 1, steps: 2.5}\n"; }),
       4,
       {"time.steps: must be a whole number; got '2.5'"}},
      {"infinite_dt",
       with([](SceneText& t) { t.time = "time: {dt: .inf, steps: 2}\n"; }),
       4,
       {"time.dt: must be a finite number", "got '.inf'"}},
      {"zero_dt",
       with([](SceneText& t) { t.time = "time:\n  dt: 0\n  steps: 2\n"; }),
       5,
       {"time.dt: must be > 0; got '0'"}},
      {"zero_faces",
       with([](SceneText& t) {
         t.geometry = "geometry: {cage: {generator: rectangle, faces: [0, 4]}}\n";
       }),
       1,
       {"geometry.cage.faces[0]: must be in 1..100000; got '0'"}},
      {"imperfection_zero_amplitude",
       with([](SceneText& t) {
         t.geometry =
             "geometry: {mesh: {generator: cylinder, radius: 1, imperfection: {amplitude: 0}}}\n";
       }),
       1,
       {"geometry.mesh.imperfection.amplitude: must be nonzero; got '0'"}},
      {"imperfection_too_deep",
       with([](SceneText& t) {
         t.geometry = "geometry:\n  mesh:\n    generator: cylinder\n    radius: 1\n"
                      "    imperfection: [{amplitude: 0.3}, {amplitude: -0.2, phase: 1}]\n";
       }),
       5,
       {"geometry.mesh.imperfection: its amplitudes add up to half the radius or more"}},
      {"imperfection_unknown_key",
       with([](SceneText& t) {
         t.geometry = "geometry:\n  mesh: {generator: cylinder, imperfection: {amplitude: 0.1, "
                      "wave: [1, 1]}}\n";
       }),
       2,
       {"geometry.mesh.imperfection", "wave"}},
      {"bodies_on_a_cage",
       with([](SceneText& t) { t.extra = "bodies: [{name: b, mesh: {generator: sphere}}]\n"; }),
       5,
       {"bodies: several bodies need triangle meshes", "geometry: {mesh: {...}}"}},
      {"bodies_same_name",
       with([&](SceneText& t) {
         triangle_mesh(t);
         t.extra = "bodies:\n  - {name: b, mesh: {generator: sphere}}\n"
                   "  - {name: b, mesh: {generator: sphere}}\n";
       }),
       6,
       {"bodies[1].name: names another body already; got 'b'"}},
      {"bodies_other_bending",
       with([&](SceneText& t) {
         triangle_mesh(t);
         t.extra = "bodies:\n  - name: b\n    mesh: {generator: sphere}\n"
                   "    material: {model: neo-hookean, youngs_modulus: 1e6, poisson_ratio: 0.3, "
                   "thickness: 1e-3, volume_density: 1, bending: midedge}\n";
       }),
       7,
       {"bodies[0].material: every body bends by the same model", "bending: hinge"}},
      {"bodies_unknown_key",
       with([&](SceneText& t) {
         triangle_mesh(t);
         t.extra = "bodies: [{name: b, mesh: {generator: sphere}, offset: [0, 0, 1]}]\n";
       }),
       4,
       {"bodies[0]", "offset"}},
      {"unknown_generator",
       with([](SceneText& t) { t.geometry = "geometry: {cage: {generator: circle}}\n"; }),
       1,
       {"geometry.cage.generator: unknown generator; got 'circle'", "rectangle or l-shape"}},
      {"default_cut_misfits",
       with([](SceneText& t) {
         t.geometry = "geometry: {cage: {generator: l-shape, faces: [4, 4]}}\n";
       }),
       1,
       {"geometry.cage: cut[0] (default 0.3) must be a whole number of faces", "give `cut:"}},
      {"cut_leaves_no_face",
       with([](SceneText& t) {
         t.geometry = "geometry:\n  cage: {generator: l-shape, faces: [4, 4], cut: [1.0, 0.5]}\n";
       }),
       2,
       {"geometry.cage.cut[0]: must be in (0, 1); got '1.0'"}},
      {"corner_cut_away",
       with([](SceneText& t) {
         t.geometry = "geometry: {cage: {generator: l-shape, faces: [10, 10]}}\n";
         t.extra = "probes: {p: corner(top-right)}\n";
       }),
       5,
       {"probes.p: lies in the block cut away", "got 'corner(top-right)'"}},
      {"hierarchy_on_a_cage",
       with([](SceneText& t) {
         t.geometry = "geometry: {cage: {generator: rectangle}, hierarchy: {levels: 3}}\n";
       }),
       1,
       {"geometry.hierarchy: hierarchy applies to triangle meshes", "refine"}},
      {"hierarchy_ratio_one",
       with([](SceneText& t) {
         t.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {levels: 3, ratio: 1}}\n";
         t.material = kTriangleMaterial;
       }),
       1,
       {"geometry.hierarchy.ratio: each level must have fewer vertices", "got '1'", "(1, 64]"}},
      {"hierarchy_one_level",
       with([](SceneText& t) {
         t.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {levels: 1}}\n";
         t.material = kTriangleMaterial;
       }),
       1,
       {"geometry.hierarchy.levels: must be in 2..12; got '1'"}},
      {"hierarchy_vertices_increase",
       with([](SceneText& t) {
         t.geometry = "geometry:\n  mesh: {generator: sphere}\n  hierarchy: {vertices: [100, 200]}\n";
         t.material = kTriangleMaterial;
       }),
       3,
       {"geometry.hierarchy.vertices[1]: each coarse level must have fewer vertices", "got '200'"}},
      {"hierarchy_both",
       with([](SceneText& t) {
         t.geometry =
             "geometry: {mesh: {generator: sphere}, hierarchy: {vertices: [100], levels: 2}}\n";
         t.material = kTriangleMaterial;
       }),
       1,
       {"geometry.hierarchy.levels: give either levels (with ratio) or vertices, not both"}},
      {"hierarchy_unknown_key",
       with([](SceneText& t) {
         t.geometry = "geometry: {mesh: {generator: sphere}, hierarchy: {level: 3}}\n";
         t.material = kTriangleMaterial;
       }),
       1,
       {"geometry.hierarchy", "level", "levels"}},
      {"unknown_model",
       with([](SceneText& t) {
         t.material = "material: {model: mooney-rivlin, thickness: 1, density: 1}\n";
       }),
       2,
       {"material.model: unknown material model; got 'mooney-rivlin'"}},
      {"unknown_preset",
       with([](SceneText& t) {
         t.material = "material: {model: clyde-orthotropic, preset: silk}\n";
       }),
       2,
       {"material.preset: unknown preset; got 'silk'",
        "(expected denim (Table 1 with the coupling limit) or denim-table1"}},
      {"zero_alpha",
       with([](SceneText& t) {
         t.material =
             "material: {model: clyde-orthotropic, preset: denim, alpha: [[1], [0], [1], [1]]}\n";
       }),
       2,
       {"material.alpha[1][0]: must be nonzero; got '0'"}},
      {"mu_alpha_lengths_differ",
       with([](SceneText& t) {
         t.material =
             "material: {model: clyde-orthotropic, preset: denim, mu: [[1], [1], [1], [1]]}\n";
       }),
       2,
       {"material.mu[0]: phi_1 has 1 mu and 5 alpha entries"}},
      {"svk_takes_no_warp",
       with([](SceneText& t) {
         t.material =
             "material: {model: isotropic-svk, youngs_modulus: 1, poisson_ratio: 0,\n"
             "           thickness: 1, density: 1, warp: [1, 0, 0]}\n";
       }),
       3,
       {"material.warp: unknown key"}},
      {"zero_warp",
       with([](SceneText& t) {
         t.material = "material: {model: clyde-orthotropic, preset: denim, warp: [0, 0, 0]}\n";
       }),
       2,
       {"material.warp: must not be the zero vector"}},
      {"inertia_with_parameters",
       with([](SceneText& t) { t.effects = "effects:\n  - inertia: {mass: 2}\n"; }),
       4,
       {"effects[0].inertia: inertia takes no parameters; got '{mass: 2}'"}},
      {"bare_effect_needing_parameters",
       with([](SceneText& t) { t.effects = "effects: [line_load]\n"; }),
       3,
       {"effects[0].line_load: has no value", "a map with keys where, force_per_length, ramp"}},
      {"empty_components",
       with([](SceneText& t) {
         t.effects = "effects: [{dirichlet: {where: boundary, components: []}}]\n";
       }),
       3,
       {"effects[0].dirichlet.components: must name at least one component; got '[]'"}},
      {"box_min_above_max",
       with([](SceneText& t) {
         t.effects = "effects:\n  - clamp: {where: {box: {min: [0, 0, 1], max: [1, 1, 0]}}}\n";
       }),
       4,
       {"effects[0].clamp.where.box: min must be <= max", "component 2"}},
      {"where_map_with_both_forms",
       with([](SceneText& t) {
         t.effects =
             "effects:\n  - point_load: {where: {at: [0, 0, 0], box: {}}, force: [0, 0, 1]}\n";
       }),
       4,
       {"effects[0].point_load.where: a where-map has exactly one of the keys"}},
      {"unquoted_point_in_flow_map",
       with(
           [](SceneText& t) { t.effects = "effects:\n  - dirichlet: {where: point(0.5, 0.5)}\n"; }),
       4,
       {"effects[0].dirichlet.0.5): unknown key", "quote the value"}},
      {"negative_penalty",
       with([](SceneText& t) {
         t.effects = "effects: [{clamp: {where: boundary, penalty: -1}}]\n";
       }),
       3,
       {"effects[0].clamp.penalty: must be > 0; got '-1'"}},
      {"ramp_not_boolean",
       with([](SceneText& t) {
         t.effects = "effects: [{surface_load: {force_per_area: [0, 0, 1], ramp: 1}}]\n";
       }),
       3,
       {"effects[0].surface_load.ramp: must be a boolean; got '1'", "true or false"}},
      {"duplicate_gravity",
       with([](SceneText& t) { t.effects = "effects:\n  - gravity\n  - gravity: [0, 0, -1]\n"; }),
       5,
       {"effects[1]: gravity may appear only once (first given at line 4)"}},
      {"checkpoint_with_affine",
       with([](SceneText& t) {
         t.extra =
             "initial_state: {checkpoint: scene.yaml, affine: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n";
       }),
       5,
       {"initial_state.checkpoint: a checkpoint holds the whole state"}},
      {"samples_out_of_range",
       with([](SceneText& t) { t.extra = "output: {samples_per_face: 17}\n"; }),
       5,
       {"output.samples_per_face: must be in 1..16; got '17'"}},
      {"repeated_format",
       with([](SceneText& t) { t.extra = "output: {formats: [csv, csv]}\n"; }),
       5,
       {"output.formats[1]: format given twice; got 'csv'"}},
      {"bad_probe_name",
       with([](SceneText& t) { t.extra = "probes: {\"a,b\": {at: [0, 0, 0]}}\n"; }),
       5,
       {"probes.a,b: probe names may hold only", "got 'a,b'"}},
      {"motion_without_translate_or_rotate",
       with([](SceneText& t) {
         t.effects = "effects:\n  - dirichlet: {where: boundary(left), motion: {over: [0, 1]}}\n";
       }),
       4,
       {"effects[0].dirichlet.motion: a motion needs `translate`, `rotate` or both"}},
      {"rotation_without_angle",
       with([](SceneText& t) {
         t.effects =
             "effects:\n  - clamp: {where: boundary(left), motion: {rotate: {axis: [1, 0, 0], "
             "center: [0, 0, 0]}, over: [0, 1]}}\n";
       }),
       4,
       {"effects[0].clamp.motion.rotate.angle: required key is missing", "radians"}},
      {"rotation_infinite_angle",
       with([](SceneText& t) {
         t.effects =
             "effects:\n  - clamp: {where: boundary(left), motion: {rotate: {axis: [1, 0, 0], "
             "center: [0, 0, 0], angle: .inf}, over: [0, 1]}}\n";
       }),
       4,
       {"effects[0].clamp.motion.rotate.angle: must be a finite number", "got '.inf'"}},
      {"rotation_centre_nan",
       with([](SceneText& t) {
         t.effects =
             "effects:\n  - clamp: {where: boundary(left), motion: {rotate: {axis: [1, 0, 0], "
             "center: [0, .nan, 0], angle: 1}, over: [0, 1]}}\n";
       }),
       4,
       {"effects[0].clamp.motion.rotate.center[1]: must be a finite number"}},
      {"missing_time",
       with([](SceneText& t) { t.time = ""; }),
       1,
       {"time: required key is missing"}},
      {"missing_cage",
       with([](SceneText& t) { t.geometry = "geometry: {refine: 1}\n"; }),
       1,
       {"geometry.cage: required key is missing"}},
      {"steps_too_many",
       with([](SceneText& t) { t.time = "time: {dt: 1, steps: 1e7}\n"; }),
       4,
       {"time.steps: must be in 1..1000000; got '1e7'"}},
      {"section_not_a_map",
       with([](SceneText& t) { t.time = "time: [1, 2]\n"; }),
       4,
       {"time: must be a map", "got '[1, 2]'", "a map with keys dt, steps"}},
  };
  ScratchDir dir;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    expect_scene_error(dir.write(c.name + ".yaml", c.text.str()), c.line, c.fragments);
  }
}

TEST(SceneErrors, UnreadableEmptyAndMultiDocumentFiles) {
  ScratchDir dir;
  const fs::path absent = dir.path() / "absent.yaml";
  EXPECT_EQ(scene_error(absent), absent.string() + ": cannot read the scene file: no such file");
  expect_scene_error(dir.write("empty.yaml", "# nothing\n"), 1, {"the scene file is empty"});
  expect_scene_error(dir.write("two.yaml", SceneText{}.str() + "---\n" + SceneText{}.str()), 6,
                     {"a scene file holds one YAML document; got 2"});
}

// ---------------------------------------------------------------------------------------------
// The --help reference

TEST(SceneFormatHelp, IsWrappedAndOfReferenceLength) {
  std::istringstream help(scene_format_help());
  int lines = 0;
  for (std::string line; std::getline(help, line); ++lines) {
    EXPECT_LE(line.size(), 100u) << line;
    EXPECT_EQ(line.find('\t'), std::string::npos) << line;
  }
  EXPECT_GE(lines, 80);
  EXPECT_LE(lines, 140);
}

TEST(SceneFormatHelp, NamesEveryKey) {
  const std::string help = scene_format_help();
  for (const char* key : {"name:",
                          "geometry:",
                          "cage:",
                          "generator: rectangle",
                          "l-shape",
                          "size:",
                          "faces:",
                          "cut:",
                          "origin:",
                          "obj:",
                          "refine:",
                          "material:",
                          "bodies:",
                          "self_contact:",
                          "model: clyde-orthotropic",
                          "preset: denim",
                          "k:",
                          "mu:",
                          "alpha:",
                          "warp:",
                          "model: isotropic-svk",
                          "youngs_modulus:",
                          "poisson_ratio:",
                          "thickness:",
                          "density:",
                          "thickness_points:",
                          "bending: hinge | midedge",
                          "diagonals:",
                          "effects:",
                          "inertia",
                          "gravity:",
                          "surface_load:",
                          "force_per_area:",
                          "line_load:",
                          "force_per_length:",
                          "point_load:",
                          "force:",
                          "ramp",
                          "dirichlet:",
                          "components",
                          "motion",
                          "translate:",
                          "over:",
                          "sigma",
                          "penalty",
                          "clamp:",
                          "rotation_penalty",
                          "initial_state:",
                          "affine:",
                          "checkpoint:",
                          "time:",
                          "dt:",
                          "steps:",
                          "probes:",
                          "output:",
                          "dir:",
                          "every:",
                          "formats:",
                          "samples_per_face:",
                          "checkpoint_every:",
                          "solver:",
                          "options_file:",
                          "boundary(SIDE)",
                          "corner(CORNER)",
                          "point(u, v)",
                          "{at: [x, y, z]}",
                          "{box: {min:"}) {
    EXPECT_NE(help.find(key), std::string::npos) << key;
  }
}

// --help's example is examples/drape.yaml (the main job, and the README's scene), line for line
// without its comment lines, and it parses.
TEST(SceneFormatHelp, ExampleIsTheMainJobsDrape) {
  const std::string help = scene_format_help();
  const std::size_t title = help.find("\nEXAMPLE");
  ASSERT_NE(title, std::string::npos);
  std::istringstream example(help.substr(help.find('\n', title + 1) + 1));
  std::string yaml;
  for (std::string line; std::getline(example, line);)
    yaml += line.substr(std::min<std::size_t>(2, line.size())) + "\n";
  std::ifstream file(kData / ".." / ".." / "examples" / "drape.yaml");
  ASSERT_TRUE(file) << "examples/drape.yaml";
  std::string drape;
  for (std::string line; std::getline(file, line);)
    if (!line.empty() && line[0] != '#') drape += line + "\n";
  EXPECT_EQ(yaml, drape);
  ScratchDir dir;
  const Scene scene = parse_scene(dir.write("example.yaml", yaml));
  EXPECT_EQ(scene.effects.size(), 4u);
  EXPECT_TRUE(scene.has_inertia());
}

}  // namespace
}  // namespace mlshell
