// The effects of a scene on a triangle mesh (see triangle_effect_builder.hpp).
#include "mlshell/triangle/triangle_effect_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <iomanip>
#include <sstream>

#include "mlshell/contact/collider_meshes.hpp"
#include "mlshell/contact/contact_term.hpp"
#include "mlshell/effect_builder.hpp"
#include "mlshell/effects.hpp"
#include "mlshell/triangle/triangle_bodies.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
#include "mlshell/triangle/triangle_generators.hpp"
#include "mlshell/triangle/triangle_selection.hpp"

namespace mlshell {

namespace {

bool owns(const ParallelLayout& layout, int vertex) {
  const int local = layout.local_of(vertex);
  return local >= 0 && local < layout.num_owned_points();
}

/// Consistent nodal forces of a force per area f: f Ā_t / 3 to each vertex of each triangle,
/// times scale[t] if given (the area density, for gravity).
std::vector<double> area_force(const TriangleDiscretization& disc, const ParallelLayout& layout,
                               const Vec3& f, const std::vector<double>* scale = nullptr) {
  std::vector<double> force(3 * layout.num_local_points(), 0.0);
  const auto& X = disc.points();
  for (int e : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[e];
    const double area = 0.5 * (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).norm();
    const double s = scale ? (*scale)[e] : 1.0;
    for (int v : t)
      for (int c = 0; c < 3; ++c) force[3 * layout.local_of(v) + c] += s * f[c] * area / 3.0;
  }
  return force;
}

/// Nodal weights of a selection: half the length of each selected boundary edge at a vertex,
/// or h for a selected vertex on no selected boundary edge; each vertex on its owner rank.
std::vector<std::pair<int, double>> vertex_weights(const TriangleDiscretization& disc,
                                                   const ParallelLayout& layout,
                                                   const std::vector<int>& vertices) {
  std::vector<double> length(disc.num_points(), 0.0);
  for (const auto& [a, b] : selected_boundary_edges(disc, vertices)) {
    const double l = (disc.points()[b] - disc.points()[a]).norm();
    length[a] += 0.5 * l;
    length[b] += 0.5 * l;
  }
  std::vector<std::pair<int, double>> out;
  for (int v : vertices)
    if (owns(layout, v)) out.emplace_back(v, length[v] > 0.0 ? length[v] : disc.mesh_size());
  return out;
}

std::vector<int> curve_vertices(const TriangleDiscretization& disc, const Where& where,
                                const CageFrame& frame) {
  return select_vertices(disc, std::get<CurveSelection>(where.selection), frame, where.text);
}

/// The contact term of the scene's `contact` effect with all its colliders (contact_term.hpp).
std::unique_ptr<ContactTerm> build_contact_term(const Scene& scene, const ContactEffect& c,
                                                const TriangleDiscretization& disc,
                                                const ParallelLayout& layout,
                                                const TriangleBodies& bodies) {
  const double membrane_stiffness = bodies.max_membrane_stiffness();
  const TriangleMesh& mesh = disc.mesh();
  Point3 lo = Point3::Constant(INFINITY), hi = Point3::Constant(-INFINITY);
  for (const Point3& X : mesh.points) lo = lo.cwiseMin(X), hi = hi.cwiseMax(X);
  double area = 0.0, edges = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Point3 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &d = mesh.points[t[2]];
    area += 0.5 * (b - a).cross(d - a).norm();
    edges += (b - a).norm() + (d - b).norm() + (a - d).norm();
  }
  const double diagonal = (hi - lo).norm(), edge_length = edges / (3.0 * mesh.num_triangles());
  ContactSettings settings;
  // Several bodies: the mid-surfaces keep the thickest body's thickness apart.
  settings.barrier = ContactBarrier::from(c.thickness.value_or(bodies.max_thickness()),
                                          c.gap.value_or(1e-3 * diagonal));
  settings.self_contact = c.self;
  settings.body_of_point = bodies.of_point;
  settings.self_contact_of_body.assign(1, c.self);
  for (const BodySpec& b : scene.bodies)
    settings.self_contact_of_body.push_back(b.self_contact.value_or(c.self));
  settings.stiffness = c.stiffness.value_or(0.0);
  std::vector<double> body_area(bodies.size(), 0.0);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Point3 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &d = mesh.points[t[2]];
    body_area[bodies.of_face[f]] += 0.5 * (b - a).cross(d - a).norm();
  }
  double mass = 0.0;
  for (int b = 0; b < bodies.size(); ++b) mass += bodies.materials[b]->density * body_area[b];
  settings.average_mass = mass / mesh.num_points();
  settings.bbox_diagonal = diagonal;
  // The force per vertex: the distributed loads' share, at least that of a membrane strained
  // by 10⁻⁴ ĝ/ℓ over an edge (for scenes driven by motions alone).
  double per_area = 0.0;
  for (const Effect& e : scene.effects) {
    if (const auto* g = std::get_if<GravityEffect>(&e))
      per_area += bodies.max_area_density() *
                  std::hypot(g->acceleration[0], g->acceleration[1], g->acceleration[2]);
    else if (const auto* s = std::get_if<SurfaceLoadEffect>(&e))
      per_area += std::hypot(s->force_per_area[0], s->force_per_area[1], s->force_per_area[2]);
    else if (const auto* p = std::get_if<PressureEffect>(&e))
      per_area += std::abs(p->pressure);
  }
  settings.vertex_force = std::max(per_area * area / mesh.num_points(),
                                   1e-4 * membrane_stiffness * settings.barrier.gap);
  // The most: the loads' share, or a membrane stretched to twice its length across an edge.
  settings.max_vertex_force = std::max(settings.vertex_force, membrane_stiffness * edge_length);
  std::vector<TriangleMesh> obstacles;
  for (const Effect& e : scene.effects)
    if (const auto* collider = std::get_if<ColliderEffect>(&e))
      obstacles.push_back(make_collider_mesh(*collider, lo, hi, edge_length));
  try {
    return std::make_unique<ContactTerm>("contact", mesh, layout, std::move(obstacles), settings);
  } catch (const std::invalid_argument& e) {
    throw SceneError(e.what());
  }
}

}  // namespace

TriangleMesh build_triangle_mesh(const TriangleMeshSpec& s) {
  using G = TriangleMeshSpec::Generator;
  switch (s.generator) {
    case G::kObj:
      return read_obj_triangles(s.obj);
    case G::kRectangle: {
      TriangleMesh mesh =
          s.edge_length ? make_unstructured_rectangle(s.size[0], s.size[1], *s.edge_length,
                                                      s.origin[0], s.origin[1])
                        : make_triangle_rectangle(s.size[0], s.size[1], s.faces[0], s.faces[1],
                                                  s.origin[0], s.origin[1], s.uniform_diagonals);
      if (s.relief_amplitude != 0.0)
        for (Point3& X : mesh.points) {
          const double u = (X.x() - s.origin[0]) / s.size[0], v = (X.y() - s.origin[1]) / s.size[1];
          const double bu = std::sin(std::numbers::pi * s.relief_bumps[0] * u);
          const double bv = std::sin(std::numbers::pi * s.relief_bumps[1] * v);
          X.z() += s.relief_amplitude * bu * bu * bv * bv;
        }
      return mesh;
    }
    case G::kCylinder: {
      TriangleMesh mesh = make_cylinder(s.radius, s.length, s.faces[0], s.faces[1]);
      for (Point3& X : mesh.points) {
        const double theta = std::atan2(X.y(), X.x());
        double dr = 0.0;
        for (const TriangleMeshSpec::WallMode& m : s.imperfection)
          dr += m.amplitude * std::cos(m.waves[0] * theta + m.phase) *
                std::sin(std::numbers::pi * m.waves[1] * X.z() / s.length);
        X.x() *= 1.0 + dr / s.radius;
        X.y() *= 1.0 + dr / s.radius;
      }
      return mesh;
    }
    case G::kDome:
      return make_spherical_cap(s.radius, s.opening_angle, s.rings);
    case G::kSphere:
      return make_sphere(s.radius, s.subdivisions);
  }
  throw MeshError("unknown mesh generator");
}

std::unique_ptr<LevelProblem> build_triangle_problem(const Scene& scene,
                                                     const TriangleDiscretization& disc,
                                                     const ParallelLayout& layout,
                                                     const CageFrame& frame, double penalty_h) {
  const TriangleBodies bodies = TriangleBodies::of(scene, disc.mesh());
  std::vector<TriangleShellParameters> body_params;
  for (int b = 0; b < bodies.size(); ++b) body_params.push_back(bodies.parameters(b));
  auto problem = std::make_unique<LevelProblem>(layout);
  problem->add_term(
      std::make_unique<TriangleElasticTerm>(disc, layout, body_params, bodies.of_face));
  const std::vector<double> rho = bodies.face_area_density();  // area density ρτ per face
  if (scene.time.quasistatic())
    problem->add_term(std::make_unique<TriangleInertiaTerm>(disc, layout, rho,
                                                            scene.time.proximal_step, "proximal"));
  const double ramp_time = scene.time.dt * scene.time.steps;
  const double h = penalty_h > 0.0 ? penalty_h : disc.mesh_size();
  Point3 lo = Point3::Constant(INFINITY), hi = Point3::Constant(-INFINITY);
  for (const Point3& X : disc.points()) lo = lo.cwiseMin(X), hi = hi.cwiseMax(X);
  // The penalties hold the stiffest body.
  const PenaltyScale scale{bodies.max_membrane_stiffness(), (hi - lo).maxCoeff()};
  const int nlocal = layout.num_local_points();
  add_effect_terms(scene, *problem, "", [&](const Effect& effect, const std::string& name) {
    if (std::holds_alternative<InertiaEffect>(effect)) {
      problem->add_term(std::make_unique<TriangleInertiaTerm>(disc, layout, rho, scene.time.dt));
    } else if (const auto* g = std::get_if<GravityEffect>(&effect)) {
      problem->add_term(std::make_unique<LinearLoadTerm>(
          name, area_force(disc, layout, g->acceleration, &rho), 0.0));
    } else if (const auto* s = std::get_if<SurfaceLoadEffect>(&effect)) {
      problem->add_term(std::make_unique<LinearLoadTerm>(
          name, area_force(disc, layout, s->force_per_area), s->ramp ? ramp_time : 0.0));
    } else if (const auto* l = std::get_if<LineLoadEffect>(&effect)) {
      std::vector<double> force(3 * nlocal, 0.0);
      const auto vertices = curve_vertices(disc, l->where, frame);
      for (const auto& [v, w] : vertex_weights(disc, layout, vertices))
        for (int c = 0; c < 3; ++c) force[3 * layout.local_of(v) + c] += w * l->force_per_length[c];
      problem->add_term(
          std::make_unique<LinearLoadTerm>(name, std::move(force), l->ramp ? ramp_time : 0.0));
    } else if (const auto* p = std::get_if<PointLoadEffect>(&effect)) {
      std::vector<double> force(3 * nlocal, 0.0);
      const int v =
          select_vertex(disc, std::get<PointSelection>(p->where.selection), frame, p->where.text);
      if (owns(layout, v))
        for (int c = 0; c < 3; ++c) force[3 * layout.local_of(v) + c] = p->force[c];
      problem->add_term(
          std::make_unique<LinearLoadTerm>(name, std::move(force), p->ramp ? ramp_time : 0.0));
    } else if (const auto* d = std::get_if<DirichletEffect>(&effect)) {
      const double beta = penalty_parameter(d->penalty, d->sigma, h, scale);
      std::vector<PenaltySample> samples;
      if (std::holds_alternative<PointSelection>(d->where.selection)) {
        const int v =
            select_vertex(disc, std::get<PointSelection>(d->where.selection), frame, d->where.text);
        if (owns(layout, v))
          samples.push_back({{layout.local_of(v)}, {1.0}, {}, beta, 0.0, disc.points()[v]});
      } else {
        for (const auto& [v, w] :
             vertex_weights(disc, layout, curve_vertices(disc, d->where, frame)))
          samples.push_back({{layout.local_of(v)}, {1.0}, {}, beta * w, 0.0, disc.points()[v]});
      }
      auto term = std::make_unique<PenaltyTerm>(name, std::move(samples), d->components,
                                                motion_function(d->motion));
      if (d->tolerance) term->enable_augmented_lagrangian(*d->tolerance);
      problem->add_term(std::move(term));
    } else if (const auto* c = std::get_if<ClampEffect>(&effect)) {
      const double beta = penalty_parameter(c->penalty, c->sigma, h, scale);
      const auto vertices = curve_vertices(disc, c->where, frame);
      const auto edges = selected_boundary_edges(disc, vertices);
      if (edges.empty())
        throw SceneError("where '" + c->where.text +
                         "': a clamp needs boundary edges (two neighbouring selected boundary "
                         "vertices)");
      // The slope is held with the stiffness of the clamped body's own bending.
      const int body = bodies.of_point[edges.front()[0]];
      for (const auto& edge : edges)
        if (bodies.of_point[edge[0]] != body)
          throw SceneError("where '" + c->where.text + "': a clamp holds the edges of one body; " +
                           "this selection has edges of '" + bodies.names[body] + "' and '" +
                           bodies.names[bodies.of_point[edge[0]]] +
                           "' (give each body a clamp of its own)");
      const TriangleShellParameters& params = body_params[body];
      const double k =
          hinge_stiffness(params.youngs_modulus, params.poisson_ratio, params.thickness);
      std::vector<PenaltySample> samples;
      for (const auto& [v, w] : vertex_weights(disc, layout, vertices))
        samples.push_back({{layout.local_of(v)}, {1.0}, {}, beta * w, 0.0, disc.points()[v]});
      problem->add_term(std::make_unique<PenaltyTerm>(name, std::move(samples),
                                                      std::array<bool, 3>{true, true, true},
                                                      motion_function(c->motion)));
      // The rotation: the shell's own bending stiffness unless rotation_penalty replaces it.
      if (params.bending == TriangleShellParameters::Bending::kMidedge) {
        TriangleShellParameters held = params;
        if (c->rotation_penalty)  // D = rotation_penalty
          held.youngs_modulus *=
              *c->rotation_penalty /
              plate_stiffness(params.youngs_modulus, params.poisson_ratio, params.thickness);
        problem->add_term(std::make_unique<MidedgeClampTerm>(
            name + "_rotation", disc, layout, edges, held, motion_function(c->motion)));
      } else {
        const double stiffness = c->rotation_penalty ? *c->rotation_penalty : k;
        problem->add_term(std::make_unique<ClampHingeTerm>(name + "_rotation", disc, layout, edges,
                                                           stiffness, motion_function(c->motion)));
      }
    } else if (const auto* p = std::get_if<PressureEffect>(&effect)) {
      if (!disc.topology().closed())
        throw SceneError("pressure needs a closed surface; this mesh has " +
                         std::to_string(disc.topology().boundary_loops().size()) +
                         " boundary loop(s)");
      auto term =
          std::make_unique<PressureTerm>(disc, layout, p->pressure, p->ramp ? ramp_time : 0.0);
      // Inward faces (clockwise seen from outside) enclose a negative volume: a positive
      // pressure would then deflate the surface. The same total on every rank: all throw.
      if (!(term->enclosed_volume() > 0.0)) {
        std::ostringstream message;
        message << "the closed surface encloses the volume V(X) = " << std::setprecision(6)
                << term->enclosed_volume()
                << " m^3 (expected > 0): its faces are oriented inwards, so a positive "
                   "pressure would deflate it; flip the orientation of every face (reverse "
                   "the vertex order of each face of the mesh)";
        throw SceneError(message.str());
      }
      problem->add_term(std::move(term));
    } else if (const auto* c = std::get_if<ContactEffect>(&effect)) {
      problem->add_term(build_contact_term(scene, *c, disc, layout, bodies));
    }  // colliders: part of the contact term
  });
  return problem;
}

}  // namespace mlshell
