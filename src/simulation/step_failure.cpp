// The scene's energy scale and what a failed step says (see step_failure.hpp).
#include "mlshell/step_failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>

namespace mlshell {

namespace {

double norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::string format(const char* f, double x) {
  char text[64];
  std::snprintf(text, sizeof text, f, x);
  return text;
}

double youngs_modulus(const MaterialSpec& m) {
  return std::visit(
      [](const auto& model) {
        using T = std::decay_t<decltype(model)>;
        if constexpr (std::is_same_v<T, ClydeMaterial>)
          return *std::max_element(model.k.begin(), model.k.end());
        else
          return model.youngs_modulus;
      },
      m.model);
}

/// What the scene has that bears on a failed step.
struct SceneTraits {
  bool inertia = false, supports = false, ramps = false, motions = false;
  double pressure = 0.0;
  bool pressure_ramped = false;
  std::vector<std::string> loads;  // effect names of the loads, once each
};

SceneTraits traits(const Scene& scene) {
  SceneTraits t;
  for (const Effect& e : scene.effects) {
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, InertiaEffect>) t.inertia = true;
          if constexpr (std::is_same_v<T, DirichletEffect> || std::is_same_v<T, ClampEffect>) {
            t.supports = true;
            if (x.motion) t.motions = true;
          }
          if constexpr (std::is_same_v<T, SurfaceLoadEffect> || std::is_same_v<T, LineLoadEffect> ||
                        std::is_same_v<T, PointLoadEffect>)
            t.ramps = t.ramps || x.ramp;
          if constexpr (std::is_same_v<T, PressureEffect>) {
            t.pressure = std::max(t.pressure, std::abs(x.pressure));
            t.pressure_ramped = x.ramp;
            t.ramps = t.ramps || x.ramp;
          }
          if constexpr (std::is_same_v<T, GravityEffect> || std::is_same_v<T, SurfaceLoadEffect> ||
                        std::is_same_v<T, LineLoadEffect> || std::is_same_v<T, PointLoadEffect>) {
            const std::string name = effect_name(e);
            if (std::find(t.loads.begin(), t.loads.end(), name) == t.loads.end())
              t.loads.push_back(name);
          }
        },
        e);
  }
  return t;
}

/// The causes that the scene's effects and material suggest, one "  - ...\n" line each.
std::string scene_causes(const Scene& scene, const SceneTraits& t) {
  std::string text;
  if (t.pressure > 0.0)
    text += "  - the pressure (" + format("%g", t.pressure) +
            " Pa) may exceed the shell's limit pressure: a neo-Hookean balloon has a maximum "
            "pressure, beyond which it inflates without bound; lower `pressure`" +
            (t.pressure_ramped ? "\n" : " or ramp it (`ramp: true`) over the steps\n");
  if (!t.loads.empty() && !t.supports && !t.inertia) {
    std::string names;
    for (const auto& n : t.loads) names += (names.empty() ? "" : ", ") + n;
    text += "  - nothing holds the shell against its loads (" + names +
            "): add a dirichlet or clamp effect, or the `inertia` effect (with integrator: "
            "implicit_euler)\n";
  }
  if (scene.material.preset == "denim-table1")
    text +=
        "  - the material preset denim-table1 has a negative-energy well (psi_min = -0.0205 MPa): "
        "preset denim limits it\n";
  return text;
}

/// A step size that matters, or "": dt with inertia; the load steps of quasistatic ramps and
/// motions (nothing changes with dt in a quasistatic scene without them).
std::string step_size(const SceneTraits& t) {
  if (t.inertia) return "a smaller dt (time.dt or -mlshell_dt)";
  if (t.ramps && t.motions)
    return "smaller load steps (more time.steps for the ramps, a smaller time.dt for the "
           "motions)";
  if (t.ramps) return "smaller load steps (more time.steps: ramps grow over all steps)";
  if (t.motions) return "smaller load steps (a smaller time.dt along the motions)";
  return "";
}

}  // namespace

std::string EnergyScale::describe() const {
  std::string text;
  auto add = [&](const char* what, double value) {
    if (value <= 0.0) return;
    text += (text.empty() ? "" : ", ") + std::string(what) + " " + format("%.2g J", value);
  };
  add("membrane Y*tau*A", elastic);
  add("loads |F|*l", loads);
  add("pressure p*A*l", pressure);
  return text;
}

EnergyScale energy_scale(const Scene& scene, double area, double size) {
  const MaterialSpec& m = scene.material;
  double force = 0.0, pressure = 0.0, motion = 0.0;
  for (const Effect& e : scene.effects) {
    if (const auto* g = std::get_if<GravityEffect>(&e)) force += m.density * norm(g->acceleration) * area;
    if (const auto* s = std::get_if<SurfaceLoadEffect>(&e)) force += norm(s->force_per_area) * area;
    if (const auto* l = std::get_if<LineLoadEffect>(&e)) force += norm(l->force_per_length) * size;
    if (const auto* p = std::get_if<PointLoadEffect>(&e)) force += norm(p->force);
    if (const auto* p = std::get_if<PressureEffect>(&e)) pressure += std::abs(p->pressure);
    if (const auto* d = std::get_if<DirichletEffect>(&e); d && d->motion)
      motion = std::max(motion, d->motion->reach(size));
    if (const auto* c = std::get_if<ClampEffect>(&e); c && c->motion)
      motion = std::max(motion, c->motion->reach(size));
  }
  double distance = size + motion;
  const double mass = m.density * area;
  if (scene.has_inertia() && mass > 0.0) {
    const double duration = scene.time.dt * scene.time.steps;
    distance += 0.5 * (force + pressure * area) / mass * duration * duration;
  }
  EnergyScale s;
  s.elastic = youngs_modulus(m) * m.thickness * area;
  s.loads = force * distance;
  s.pressure = pressure * area * distance;
  return s;
}

double reference_area(const Discretization& disc) {
  const auto& X = disc.points();
  double area = 0.0;
  for (int face : disc.elements()) {
    // Half the norm of the vector area Σ x_i × x_{i+1}: exact for triangles, and for a
    // quadrilateral half the cross product of its diagonals.
    const std::vector<int> c = disc.corners(face);
    double a[3] = {0.0, 0.0, 0.0};
    for (size_t i = 0; i < c.size(); ++i) {
      const Point3& p = X[c[i]];
      const Point3& q = X[c[(i + 1) % c.size()]];
      a[0] += p[1] * q[2] - p[2] * q[1];
      a[1] += p[2] * q[0] - p[0] * q[2];
      a[2] += p[0] * q[1] - p[1] * q[0];
    }
    area += 0.5 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  return area;
}

double reference_size(const Discretization& disc) {
  const double inf = std::numeric_limits<double>::infinity();
  double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};
  for (const Point3& p : disc.points())
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(p[k]));
      hi[k] = std::max(hi[k], static_cast<double>(p[k]));
    }
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0.0;
  return std::sqrt(d2);
}

std::string unbounded_energy_causes(const Scene& scene) {
  const SceneTraits t = traits(scene);
  std::string text = scene_causes(scene, t);
  if (const std::string s = step_size(t); !s.empty()) text += "  - " + s + "\n";
  if (text.empty())
    text = "  - the effects leave the shell free to move without bound: check the loads and "
           "boundary conditions\n";
  return text;
}

std::string not_converged_remedies(const Scene& scene, bool snes) {
  const SceneTraits t = traits(scene);
  std::vector<std::string> items{
      snes ? "more iterations (-snes_max_it)" : "more iterations (-tao_max_it)",
      snes ? "another solver (-snes_type, or -mlshell_step_solver tao)"
           : "another solver (-tao_type)"};
  if (std::string s = step_size(t); !s.empty()) items.push_back(std::move(s));
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  text += ".\n";
  if (const std::string causes = scene_causes(scene, t); !causes.empty())
    text += "Possible causes in this scene:\n" + causes;
  return text;
}

}  // namespace mlshell
