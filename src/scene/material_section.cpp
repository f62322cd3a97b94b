// The `material:` section: the orthotropic woven-cloth model of the paper's eq. (3.3)-(3.4)
// (`clyde-orthotropic`, from a preset and/or explicit k, mu, alpha) or isotropic
// St. Venant-Kirchhoff (`isotropic-svk`).
#include <cmath>
#include <stdexcept>
#include <string>

#include "mlshell/shell/material.hpp"
#include "scene_sections.hpp"

namespace mlshell::scene_reading {
namespace {

/// `mu:` or `alpha:`: four non-empty lists of numbers, one per phi_j. An alpha of 0 would make
/// its term (u+1)^alpha - 1 vanish, so alpha entries must be nonzero.
std::array<std::vector<double>, 4> read_phi_rows(const Field& field, bool nonzero) {
  std::array<std::vector<double>, 4> rows;
  const std::vector<Field> items =
      field.items(4, "four lists, one per phi_j: [[...], [...], [...], [...]]");
  for (std::size_t j = 0; j < 4; ++j) {
    const std::vector<Field> entries = items[j].items();
    items[j].check(!entries.empty(), "must have at least one entry", "a list of numbers");
    for (const Field& entry : entries) {
      const double value = entry.number();
      if (nonzero) entry.check(value != 0.0, "must be nonzero");
      rows[j].push_back(value);
    }
  }
  return rows;
}

/// With a preset every parameter is optional (it overrides the preset); without one it is required.
std::optional<Field> find_or_require(const Field& material, std::string_view key,
                                     std::string_view expected, bool has_preset) {
  if (has_preset) return material.find(key);
  return material.require(key, expected);
}

/// `coupling_limit: none` or `{onset: θ_o, bound: θ_b}` with 0 < θ_o < θ_b < 1.
void read_coupling_limit(const Field& field, ClydeMaterial& clyde) {
  constexpr std::string_view expected = "none, or {onset: a, bound: b} with 0 < a < b < 1";
  if (field.is_scalar()) {
    field.check(field.string() == "none", "unknown value", expected);
    clyde.coupling_limit.enabled = false;
    return;
  }
  field.check(field.is_map(), "must be none or a map", expected);
  field.expect_keys({"onset", "bound"});
  CouplingLimit limit;
  limit.enabled = true;
  const Field onset = field.require("onset", "a number in (0, 1)");
  const Field bound = field.require("bound", "a number in (0, 1)");
  limit.onset = onset.number();
  limit.bound = bound.number();
  bound.check(limit.bound > 0.0 && limit.bound < 1.0, "must lie in (0, 1)");
  onset.check(limit.onset > 0.0 && limit.onset < limit.bound, "must lie in (0, bound)");
  clyde.coupling_limit = limit;
}

ClydeMaterial read_clyde(const Field& material, std::string& preset) {
  ClydeMaterial clyde;
  if (const auto name = material.find("preset")) {
    preset = name->string();
    name->check(preset == "denim" || preset == "denim-table1", "unknown preset",
                "denim (Table 1 with the coupling limit) or denim-table1 (Table 1 as printed)");
    clyde = preset == "denim" ? denim_preset() : denim_table1_preset();
  }
  const bool has_preset = !preset.empty();

  if (const auto k = find_or_require(material, "k", "[k1, k2, k3, k4] in Pa", has_preset)) {
    const std::vector<Field> items = k->items(4, "[k1, k2, k3, k4] in Pa");
    for (std::size_t j = 0; j < 4; ++j) clyde.k[j] = items[j].positive_number();
  }
  const auto mu = find_or_require(material, "mu", "[[mu_11, ...], ..., [mu_41, ...]]", has_preset);
  if (mu) clyde.mu = read_phi_rows(*mu, false);
  const auto alpha =
      find_or_require(material, "alpha", "[[alpha_11, ...], ..., [alpha_41, ...]]", has_preset);
  if (alpha) clyde.alpha = read_phi_rows(*alpha, true);

  for (std::size_t j = 0; j < 4; ++j) {
    if (clyde.mu[j].size() == clyde.alpha[j].size()) continue;
    // Blame what the user wrote: alpha if given, else mu (the other one comes from the preset).
    const Field& given = alpha ? *alpha : *mu;
    given.items()[j].fail(
        "phi_" + std::to_string(j + 1) + " has " + std::to_string(clyde.mu[j].size()) + " mu and " +
        std::to_string(clyde.alpha[j].size()) + " alpha entries; they must have the same number");
  }
  if (const auto limit = material.find("coupling_limit")) read_coupling_limit(*limit, clyde);
  // The response functions must be continuable (phi_j'(0) > 0, a rising range).
  try {
    ClydeOrthotropicMaterial check(clyde);
  } catch (const std::invalid_argument& e) {
    (mu ? *mu : alpha ? *alpha : material).fail(e.what());
  }
  return clyde;
}

SvkMaterial read_svk(const Field& material) {
  SvkMaterial svk;
  svk.youngs_modulus = material.require("youngs_modulus", "a number > 0, in Pa").positive_number();
  const Field poisson = material.require("poisson_ratio", "a number in (-1, 0.5)");
  svk.poisson_ratio = poisson.number();
  poisson.check(svk.poisson_ratio > -1.0 && svk.poisson_ratio < 0.5, "must be in (-1, 0.5)");
  return svk;
}

}  // namespace

MaterialSpec read_material(const Field& material) {
  const Field model = material.require(
      "model",
      "clyde-orthotropic or isotropic-svk (cages), neo-hookean or st-venant-kirchhoff "
      "(triangle meshes)");
  const std::string model_name = model.string();
  MaterialSpec spec;
  if (model_name == "neo-hookean" || model_name == "st-venant-kirchhoff") {
    material.expect_keys(
        {"model", "youngs_modulus", "poisson_ratio", "thickness", "volume_density", "bending"});
    const SvkMaterial iso = read_svk(material);
    TriangleMaterial triangle;
    triangle.neo_hookean = model_name == "neo-hookean";
    triangle.youngs_modulus = iso.youngs_modulus;
    triangle.poisson_ratio = iso.poisson_ratio;
    if (const auto bending = material.find("bending")) {
      const std::string name = bending->string();
      bending->check(name == "hinge" || name == "midedge", "unknown bending model",
                     "hinge (discrete hinges, paper 2) or midedge (midedge-normal plate element)");
      triangle.midedge_bending = name == "midedge";
    }
    spec.model = triangle;
    spec.thickness = material.require("thickness", "a number > 0, in m").positive_number();
    const Field rho = material.require("volume_density", "a number >= 0, in kg/m³");
    rho.check(rho.number() >= 0.0, "must be >= 0");
    spec.density = rho.number() * spec.thickness;
    return spec;
  }
  if (model_name == "clyde-orthotropic") {
    material.expect_keys({"model", "preset", "thickness", "density", "warp", "thickness_points",
                          "k", "mu", "alpha", "coupling_limit"});
    spec.model = read_clyde(material, spec.preset);
  } else if (model_name == "isotropic-svk") {
    material.expect_keys(
        {"model", "youngs_modulus", "poisson_ratio", "thickness", "density", "thickness_points"});
    spec.model = read_svk(material);
  } else {
    model.fail("unknown material model",
               "clyde-orthotropic or isotropic-svk (cages), neo-hookean or st-venant-kirchhoff "
               "(triangle meshes)");
  }

  const bool denim = spec.preset.rfind("denim", 0) == 0;
  const auto thickness = find_or_require(material, "thickness", "a number > 0, in m", denim);
  spec.thickness = thickness ? thickness->positive_number() : kDenimThickness;
  const auto density = find_or_require(material, "density", "a number >= 0, in kg/m²", denim);
  spec.density = kDenimDensity;
  if (density) {
    spec.density = density->number();
    density->check(spec.density >= 0.0, "must be >= 0");
  }
  if (const auto warp = material.find("warp")) {
    spec.warp = warp->numbers<3>("[x, y, z], the warp direction");
    warp->check(std::hypot(spec.warp[0], spec.warp[1], spec.warp[2]) > 0.0,
                "must not be the zero vector");
  }
  if (const auto points = material.find("thickness_points")) {
    spec.thickness_points = points->integer_in(1, 8);
  }
  return spec;
}

}  // namespace mlshell::scene_reading
