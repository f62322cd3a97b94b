// The `effects:` list: each item is a bare name (`inertia`, `gravity`) or a single-key map
// `{name: parameters}`. Only the effects listed here are built by the simulation.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>

#include "scene_sections.hpp"

namespace mlshell::scene_reading {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kVector = "[x, y, z]";

bool optional_ramp(const Field& params) {
  const std::optional<Field> ramp = params.find("ramp");
  return ramp ? ramp->boolean() : false;
}

std::optional<double> optional_positive(const Field& params, std::string_view key) {
  const std::optional<Field> value = params.find(key);
  return value ? std::optional<double>(value->positive_number()) : std::nullopt;
}

/// `rotate: {axis: [ax, ay, az], center: [cx, cy, cz], angle: a}` (a in radians)
Rotation read_rotation(const Field& field) {
  if (field.is_map())
    if (const std::optional<Field> degrees = field.find("degrees"))
      degrees->fail("angles are given in radians, under `angle`",
                    "angle: a in radians, e.g. angle: 1.5707963267948966 for 90 degrees");
  field.expect_keys({"axis", "center", "angle"});
  Rotation rotation;
  const Field axis = field.require("axis", "[ax, ay, az], the direction of the axis");
  rotation.axis = axis.numbers<3>("[ax, ay, az]");
  const double length = std::hypot(rotation.axis[0], rotation.axis[1], rotation.axis[2]);
  axis.check(length > 0.0 && std::isfinite(length),
             "the axis must be a non-zero vector of finite length",
             "a direction such as [1, 0, 0]");
  rotation.center =
      field.require("center", "[cx, cy, cz] in m, a point of the axis").numbers<3>("[cx, cy, cz]");
  rotation.angle = field.require("angle", "a number in radians").number();
  return rotation;
}

/// `motion: {translate: [dx, dy, dz], rotate: {...}, over: [t0, t1]}`
Motion read_motion(const Field& field) {
  field.expect_keys({"translate", "rotate", "over"});
  Motion motion;
  const std::optional<Field> translate = field.find("translate");
  const std::optional<Field> rotate = field.find("rotate");
  field.check(translate || rotate, "a motion needs `translate`, `rotate` or both",
              "{translate: [dx, dy, dz], rotate: {axis: [ax, ay, az], center: [cx, cy, cz], "
              "angle: a}, over: [t0, t1]}");
  if (translate) motion.translate = translate->numbers<3>("[dx, dy, dz] in m");
  if (rotate) motion.rotate = read_rotation(*rotate);
  const Field over = field.require("over", "[t0, t1] in s");
  motion.over = over.numbers<2>("[t0, t1]");
  over.check(motion.over[0] <= motion.over[1], "t0 must be <= t1");
  return motion;
}

std::optional<Motion> optional_motion(const Field& params) {
  const std::optional<Field> motion = params.find("motion");
  return motion ? std::optional<Motion>(read_motion(*motion)) : std::nullopt;
}

/// `components: [x, z]` → which displacement components a Dirichlet condition holds.
std::array<bool, 3> read_components(const Field& field) {
  const std::vector<Field> items = field.items();
  field.check(!items.empty(), "must name at least one component", "a list of x, y, z");
  std::array<bool, 3> held{false, false, false};
  for (const Field& item : items) {
    const std::string name = item.string();
    const std::size_t axis = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : 3;
    item.check(axis < 3, "unknown component", "x, y or z");
    item.check(!held[axis], "component given twice");
    held[axis] = true;
  }
  return held;
}

// One reader per effect: `params` is the value of `{name: params}` (null for a bare name).

Effect read_inertia(const Field& params, const GeometrySpec&, const fs::path&) {
  params.check(params.is_null() || (params.is_map() && params.entries().empty()),
               "inertia takes no parameters", "a bare `- inertia`");
  return InertiaEffect{};
}

Effect read_gravity(const Field& params, const GeometrySpec&, const fs::path&) {
  if (params.is_null()) return GravityEffect{};
  return GravityEffect{params.numbers<3>("[gx, gy, gz] in m/s², e.g. [0, 0, -9.81]")};
}

Effect read_surface_load(const Field& params, const GeometrySpec&, const fs::path&) {
  params.expect_keys({"force_per_area", "ramp"});
  return SurfaceLoadEffect{
      .force_per_area =
          params.require("force_per_area", "[fx, fy, fz] in N/m²").numbers<3>(kVector),
      .ramp = optional_ramp(params)};
}

Effect read_line_load(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.expect_keys({"where", "force_per_length", "ramp"});
  return LineLoadEffect{
      .where = read_where(params.require("where", "a curve selection"), SelectionUse::Curve,
                          "line_load", geometry),
      .force_per_length =
          params.require("force_per_length", "[fx, fy, fz] in N/m").numbers<3>(kVector),
      .ramp = optional_ramp(params)};
}

Effect read_point_load(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.expect_keys({"where", "force", "ramp"});
  return PointLoadEffect{.where = read_where(params.require("where", "a point selection"),
                                             SelectionUse::Point, "point_load", geometry),
                         .force = params.require("force", "[fx, fy, fz] in N").numbers<3>(kVector),
                         .ramp = optional_ramp(params)};
}

Effect read_dirichlet(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.expect_keys({"where", "components", "motion", "sigma", "penalty", "tolerance"});
  DirichletEffect effect;
  effect.where = read_where(params.require("where", "a selection"), SelectionUse::CurveOrPoint,
                            "dirichlet", geometry);
  if (const std::optional<Field> components = params.find("components")) {
    effect.components = read_components(*components);
  }
  effect.motion = optional_motion(params);
  effect.sigma = optional_positive(params, "sigma").value_or(effect.sigma);
  effect.penalty = optional_positive(params, "penalty");
  effect.tolerance = optional_positive(params, "tolerance");
  return effect;
}

Effect read_pressure(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.expect_keys({"pressure", "ramp"});
  params.check(geometry.triangles(), "pressure acts on closed triangle-mesh surfaces",
               "geometry: {mesh: {generator: sphere, ...}} or a closed OBJ mesh");
  return PressureEffect{.pressure = params.require("pressure", "a number in Pa").number(),
                        .ramp = optional_ramp(params)};
}

Effect read_clamp(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.expect_keys({"where", "motion", "sigma", "penalty", "rotation_penalty"});
  ClampEffect effect;
  effect.where = read_where(params.require("where", "a curve selection"), SelectionUse::Curve,
                            "clamp", geometry);
  effect.motion = optional_motion(params);
  effect.sigma = optional_positive(params, "sigma").value_or(effect.sigma);
  effect.penalty = optional_positive(params, "penalty");
  effect.rotation_penalty = optional_positive(params, "rotation_penalty");
  return effect;
}

Effect read_contact(const Field& params, const GeometrySpec& geometry, const fs::path&) {
  params.check(geometry.triangles(), "contact acts on triangle-mesh shells",
               "geometry: {mesh: {...}} (subdivision cloth has no contact yet)");
  if (params.is_null()) return ContactEffect{};
  params.expect_keys({"thickness", "gap", "self", "stiffness"});
  ContactEffect effect;
  if (const std::optional<Field> thickness = params.find("thickness")) {
    effect.thickness = thickness->number();
    thickness->check(*effect.thickness >= 0.0, "the thickness must be >= 0",
                     "a distance in m, e.g. the shell's thickness");
  }
  effect.gap = optional_positive(params, "gap");
  if (const std::optional<Field> self = params.find("self")) effect.self = self->boolean();
  effect.stiffness = optional_positive(params, "stiffness");
  return effect;
}

Effect read_collider(const Field& params, const GeometrySpec& geometry, const fs::path& scene_dir) {
  params.check(geometry.triangles(), "colliders touch triangle-mesh shells",
               "geometry: {mesh: {...}}");
  constexpr std::string_view kShapes =
      "{sphere: {center, radius}}, {plane: {point, normal}}, {box: {center, size}} or {obj: path}, "
      "and optionally motion: {translate, rotate, over}";
  params.check(params.is_map(), "a collider is one shape", kShapes);
  ColliderEffect c;
  c.motion = optional_motion(params);
  auto entries = params.entries();
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [](const auto& e) { return e.first == "motion"; }),
                entries.end());
  params.check(entries.size() == 1, "a collider is one shape", kShapes);
  const auto& [shape, field] = entries.front();
  if (shape == "sphere") {
    field.expect_keys({"center", "radius", "subdivisions"});
    c.shape = ColliderEffect::Shape::kSphere;
    c.center = field.require("center", "[x, y, z] in m").numbers<3>(kVector);
    c.radius = field.require("radius", "a length in m").positive_number();
    if (const std::optional<Field> s = field.find("subdivisions")) c.subdivisions = s->integer_in(0, 6);
  } else if (shape == "plane") {
    field.expect_keys({"point", "normal", "side"});
    c.shape = ColliderEffect::Shape::kPlane;
    c.center = field.require("point", "[x, y, z] in m, a point of the plane").numbers<3>(kVector);
    const Field normal = field.require("normal", "[nx, ny, nz], the side the shell is on");
    c.normal = normal.numbers<3>(kVector);
    const double length = std::hypot(c.normal[0], c.normal[1], c.normal[2]);
    normal.check(length > 0.0 && std::isfinite(length), "the normal must be a non-zero vector",
                 "e.g. [0, 0, 1]");
    for (double& n : c.normal) n /= length;
    c.side = optional_positive(field, "side");
  } else if (shape == "box") {
    field.expect_keys({"center", "size"});
    c.shape = ColliderEffect::Shape::kBox;
    c.center = field.require("center", "[x, y, z] in m").numbers<3>(kVector);
    const Field size = field.require("size", "[sx, sy, sz] in m");
    c.size = size.numbers<3>(kVector);
    size.check(c.size[0] > 0.0 && c.size[1] > 0.0 && c.size[2] > 0.0,
               "every edge length must be > 0");
  } else if (shape == "obj") {
    c.shape = ColliderEffect::Shape::kObj;
    c.obj = read_existing_path(field, scene_dir);
  } else {
    params.fail("unknown collider shape '" + shape + "'", kShapes);
  }
  return c;
}

/// How to read each effect, in the order of kEffectNames (and of the Effect variant).
struct EffectReader {
  Effect (*read)(const Field& params, const GeometrySpec& geometry, const fs::path& scene_dir);
  bool once;  ///< may appear at most once in a scene
};

constexpr std::array<EffectReader, kEffectNames.size()> kEffectReaders{{
    {read_inertia, true},
    {read_gravity, true},
    {read_surface_load, false},
    {read_line_load, false},
    {read_point_load, false},
    {read_dirichlet, false},
    {read_clamp, false},
    {read_pressure, false},
    {read_contact, true},
    {read_collider, false},
}};

std::string known_effects() {
  std::string list;
  for (std::string_view name : kEffectNames) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

}  // namespace

std::vector<Effect> read_effects(const Field& effects, const GeometrySpec& geometry,
                                 const fs::path& scene_dir) {
  std::vector<Effect> out;
  if (effects.is_null()) return out;  // `effects:` with nothing: only the elastic energy
  std::array<int, kEffectNames.size()> first_line{};  // line of the first use, 0 if none
  std::optional<Field> pending_collider;  // a collider given before any contact effect
  for (const Field& item : effects.items()) {
    // `- inertia` names the effect in the item itself; `- gravity: [..]` in its only key.
    std::string name;
    std::optional<Field> params;
    if (item.is_scalar()) {
      name = item.string();
      params = item.without_value(name);
    } else {
      item.check(item.is_map() && item.entries().size() == 1,
                 "an effect is a name or a single-key map {name: parameters}",
                 "e.g. `- inertia` or `- gravity: [0, 0, -9.81]`");
      std::tie(name, params) = item.entries().front();
    }

    const auto known = std::find(kEffectNames.begin(), kEffectNames.end(), name);
    if (known == kEffectNames.end()) {
      item.fail("unknown effect '" + name + "'", "one of " + known_effects());
    }
    const auto index = static_cast<std::size_t>(known - kEffectNames.begin());
    int& first = first_line[index];
    if (kEffectReaders[index].once && first != 0) {
      item.fail(name + " may appear only once (first given at line " + std::to_string(first) + ")");
    }
    if (first == 0) first = item.line();
    out.push_back(kEffectReaders[index].read(*params, geometry, scene_dir));
    if (std::holds_alternative<ColliderEffect>(out.back()) && first_line[8] == 0 &&
        !pending_collider)
      pending_collider = item;
  }
  if (pending_collider && first_line[8] == 0)
    pending_collider->fail("a collider needs a `contact` effect",
                           "add `- contact` (or `- contact: {gap: ..., self: false}`) to effects");
  return out;
}

}  // namespace mlshell::scene_reading
