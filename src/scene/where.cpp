// `where:` selections: the string forms (`boundary(left)`, `corner(top-right)`, `point(u, v)`),
// the map forms (`{at: [x, y, z]}`, `{box: {min, max}}`), and the checks that a selection fits the
// effect that uses it and the cage it refers to.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>

#include "scene_sections.hpp"

namespace mlshell {
namespace {

constexpr std::array<std::string_view, 5> kSides{"left", "right", "bottom", "top", "re-entrant"};
constexpr std::array<std::string_view, 4> kCorners{"bottom-left", "bottom-right", "top-left",
                                                   "top-right"};
constexpr std::string_view kWhereForms =
    "boundary, boundary(left|right|bottom|top|re-entrant), boundary(loop k), group(name), "
    "corner(bottom-left|bottom-right|top-left|top-right), point(u, v), {at: [x, y, z]} or "
    "{box: {min: [x, y, z], max: [x, y, z]}}";

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

template <std::size_t N>
bool is_one_of(std::string_view word, const std::array<std::string_view, N>& words) {
  return std::find(words.begin(), words.end(), word) != words.end();
}

/// `u, v` of `point(u, v)`: two finite numbers in [0, 1]; anything else goes to `fail`.
template <class Fail>
std::array<double, 2> parse_param(std::string_view args, const Fail& fail) {
  const std::size_t comma = args.find(',');
  if (comma == std::string_view::npos || args.find(',', comma + 1) != std::string_view::npos) {
    fail("point(u, v) takes two numbers", "point(u, v) with u, v in [0, 1]");
  }
  const std::array<std::string_view, 2> words{trim(args.substr(0, comma)),
                                              trim(args.substr(comma + 1))};
  std::array<double, 2> uv{};
  for (std::size_t i = 0; i < 2; ++i) {
    const std::optional<double> value = scene_reading::parse_real(words[i]);
    if (!value) fail("point(u, v): '" + std::string(words[i]) + "' is not a number", "");
    if (!std::isfinite(*value)) fail("point(u, v): NaN and Inf are not accepted", "");
    if (*value < 0.0 || *value > 1.0) {
      fail("point(u, v): " + std::string(i == 0 ? "u" : "v") + " must be in [0, 1]", "");
    }
    uv[i] = *value;
  }
  return uv;
}

/// `{at: [x, y, z]}` or `{box: {min: [...], max: [...]}}`; Where::text is `at(x, y, z)` or
/// `box([..], [..])` with the numbers as the user wrote them.
Where read_where_map(const scene_reading::Field& field) {
  using scene_reading::Field;
  field.expect_keys({"at", "box"});
  const std::optional<Field> at = field.find("at");
  const std::optional<Field> box = field.find("box");
  if (at.has_value() == box.has_value()) {
    field.fail("a where-map has exactly one of the keys `at` and `box`", kWhereForms);
  }
  // Called after numbers<3>() has validated the vector.
  auto written = [](const Field& vector) {
    std::string text;
    for (const Field& item : vector.items()) text += (text.empty() ? "" : ", ") + item.text();
    return text;
  };

  if (at) {
    PointSelection point;
    point.at = at->numbers<3>("[x, y, z]");
    return Where{point, "at(" + written(*at) + ")"};
  }
  box->expect_keys({"min", "max"});
  const Field min = box->require("min", "[x, y, z]");
  const Field max = box->require("max", "[x, y, z]");
  CurveSelection curve;
  curve.kind = CurveSelection::Kind::Box;
  curve.box_min = min.numbers<3>("[x, y, z]");
  curve.box_max = max.numbers<3>("[x, y, z]");
  for (std::size_t i = 0; i < 3; ++i) {
    box->check(curve.box_min[i] <= curve.box_max[i],
               "min must be <= max in every component (component " + std::to_string(i) + ")");
  }
  return Where{curve, "box([" + written(min) + "], [" + written(max) + "])"};
}

bool is_point(const Where& where) {
  return std::holds_alternative<PointSelection>(where.selection);
}

/// Named sides, corners and (u, v) refer to a generated cage's parameter domain.
bool needs_generated_cage(const Where& where) {
  if (const auto* curve = std::get_if<CurveSelection>(&where.selection)) {
    return curve->kind == CurveSelection::Kind::Side;
  }
  return std::get<PointSelection>(where.selection).kind != PointSelection::Kind::At;
}

bool is_re_entrant(const Where& where) {
  const auto* curve = std::get_if<CurveSelection>(&where.selection);
  return curve != nullptr && curve->kind == CurveSelection::Kind::Side &&
         curve->side == "re-entrant";
}

/// The l-shape lacks its top-right block: corner(top-right) and a point(u, v) strictly inside
/// the block name no point of the surface.
bool is_in_cut(const Where& where, const LShapeCage& l_shape) {
  const auto* point = std::get_if<PointSelection>(&where.selection);
  if (point == nullptr) return false;
  if (point->kind == PointSelection::Kind::Corner) return point->corner == "top-right";
  if (point->kind != PointSelection::Kind::Param) return false;
  return point->param[0] > 1.0 - l_shape.cut[0] / l_shape.size[0] &&
         point->param[1] > 1.0 - l_shape.cut[1] / l_shape.size[1];
}

}  // namespace

Where parse_where_text(const std::string& text, const std::string& context) {
  const auto fail = [&](const std::string& problem, std::string_view expected) {
    std::string message = context + ": " + problem + "; got '" + text + "'";
    if (!expected.empty()) message += " (expected " + std::string(expected) + ")";
    throw SceneError(message);
  };
  const std::string_view written = trim(text);
  const std::size_t open = written.find('(');
  const std::string_view name = trim(written.substr(0, open));
  std::optional<std::string_view> args;
  if (open != std::string_view::npos) {
    if (written.back() != ')') fail("unbalanced parentheses", kWhereForms);
    args = trim(written.substr(open + 1, written.size() - open - 2));
  }

  if (name == "boundary" && !args) return Where{CurveSelection{}, std::string(written)};
  if (name == "boundary" && args->substr(0, 4) == "loop") {
    const std::string number(trim(args->substr(4)));
    const std::optional<double> k = scene_reading::parse_real(number);
    if (!k || *k < 0 || *k != std::floor(*k) || *k > 1e6)
      fail("boundary(loop k) needs a loop number k = 0, 1, ...", "boundary(loop 0)");
    CurveSelection loop;
    loop.kind = CurveSelection::Kind::Loop;
    loop.loop = static_cast<int>(*k);
    return Where{loop, std::string(written)};
  }
  if (name == "group") {
    if (!args || args->empty()) fail("group(name) needs the name of an OBJ group", "group(name)");
    CurveSelection group;
    group.kind = CurveSelection::Kind::Group;
    group.group = *args;
    return Where{group, std::string(written)};
  }
  if (name == "boundary") {
    if (!is_one_of(*args, kSides)) fail("unknown side", "left, right, bottom, top or re-entrant");
    CurveSelection side;
    side.kind = CurveSelection::Kind::Side;
    side.side = *args;
    return Where{side, std::string(written)};
  }
  PointSelection point;
  if (name == "corner" && args) {
    if (!is_one_of(*args, kCorners)) {
      fail("unknown corner", "bottom-left, bottom-right, top-left or top-right");
    }
    point.kind = PointSelection::Kind::Corner;
    point.corner = *args;
  } else if (name == "point" && args) {
    point.kind = PointSelection::Kind::Param;
    point.param = parse_param(*args, fail);
  } else {
    fail("unknown selection", kWhereForms);
  }
  return Where{point, std::string(written)};
}

namespace scene_reading {

Where read_where(const Field& field, SelectionUse use, std::string_view who,
                 const GeometrySpec& geometry) {
  if (!field.is_scalar() && !field.is_map()) {
    field.fail(field.is_null() ? "has no value" : "must be a selection", kWhereForms);
  }
  const Where where =
      field.is_scalar() ? parse_where_text(field.string(), field.context()) : read_where_map(field);

  const std::string user(who);
  if (use == SelectionUse::Curve && is_point(where)) {
    field.fail(user + " needs a curve selection, not a point",
               "boundary, boundary(<side>) or {box: {min: [x, y, z], max: [x, y, z]}}");
  }
  if (use == SelectionUse::Point && !is_point(where)) {
    field.fail(user + " needs a point selection, not a curve",
               "{at: [x, y, z]}, corner(<corner>) or point(u, v)");
  }
  if (!geometry.has_frame() && needs_generated_cage(where)) {
    if (!geometry.triangles())
      field.fail("named sides, corners and point(u, v) exist only on generated cages",
                 "with an OBJ cage, {at: [x, y, z]} or {box: {min: [x, y, z], max: [x, y, z]}}");
    field.fail("named sides, corners and point(u, v) exist only on generated rectangle meshes",
               "{at: [x, y, z]}, {box: {min: [x, y, z], max: [x, y, z]}}, boundary(loop k) or "
               "group(name)");
  }
  if (const auto* curve = std::get_if<CurveSelection>(&where.selection);
      curve && !geometry.triangles() &&
      (curve->kind == CurveSelection::Kind::Loop || curve->kind == CurveSelection::Kind::Group))
    field.fail("boundary(loop k) and group(name) exist only on triangle meshes");
  if (is_re_entrant(where) &&
      (geometry.triangles() || !std::holds_alternative<LShapeCage>(geometry.cage))) {
    field.fail("boundary(re-entrant) exists only on an l-shape cage");
  }
  if (const auto* l_shape = std::get_if<LShapeCage>(&geometry.cage);
      l_shape && !geometry.triangles()) {
    field.check(!is_in_cut(where, *l_shape), "lies in the block cut away from the l-shape",
                "a point of the l-shape; its top-right corner is the cut");
  }
  return where;
}

}  // namespace scene_reading
}  // namespace mlshell
