// Readers for the sections of a scene file, shared by the files of src/scene. Each takes the
// Field of its section, validates everything in it and returns the section's struct.
#pragma once

#include <array>
#include <filesystem>
#include <string_view>
#include <variant>
#include <vector>

#include "mlshell/scene.hpp"
#include "scene_field.hpp"

namespace mlshell::scene_reading {

/// Thickness (m) and area density (kg/m²) of Table 1's denim, the defaults with `preset: denim`.
inline constexpr double kDenimThickness = 0.66e-3;
inline constexpr double kDenimDensity = 0.4;

/// A path relative to the scene file's folder (`scene_dir`) that must exist; the message for a
/// missing one names the key and the resolved path.
std::filesystem::path read_existing_path(const Field& field,
                                         const std::filesystem::path& scene_dir);

GeometrySpec read_geometry(const Field& geometry, const std::filesystem::path& scene_dir);
/// `geometry.mesh` (or a body's `mesh`): a generated triangle mesh or an OBJ file.
TriangleMeshSpec read_mesh(const Field& mesh, const std::filesystem::path& scene_dir);
MaterialSpec read_material(const Field& material);
/// The `bodies:` list: further triangle-mesh shells beside geometry.mesh (`scene.material` and
/// `geometry` are read already).
std::vector<BodySpec> read_bodies(const Field& bodies, const Scene& scene,
                                  const std::filesystem::path& scene_dir);

/// What kind of selection a `where:` must be for its user.
enum class SelectionUse { Curve, Point, CurveOrPoint };

/// Reads a `where:` value and checks that it fits its user (`who`, e.g. "line_load") and the cage:
/// named sides, corners and point(u, v) exist only on generated cages, re-entrant only on l-shapes.
Where read_where(const Field& where, SelectionUse use, std::string_view who,
                 const GeometrySpec& geometry);

/// Effect names as scenes write them, in the order of the Effect variant's alternatives.
inline constexpr std::array<std::string_view, 10> kEffectNames{
    "inertia",   "gravity", "surface_load", "line_load", "point_load",
    "dirichlet", "clamp",   "pressure",     "contact",   "collider"};
static_assert(std::variant_size_v<Effect> == kEffectNames.size());

/// The `effects:` list; paths (a collider's obj) are relative to `scene_dir`.
std::vector<Effect> read_effects(const Field& effects, const GeometrySpec& geometry,
                                 const std::filesystem::path& scene_dir);

}  // namespace mlshell::scene_reading
