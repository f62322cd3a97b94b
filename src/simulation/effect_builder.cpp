// From scene effects to energy terms: quadrature of loads and penalty samples on this rank's
// elements, boundary edges and points.
#include "mlshell/effect_builder.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "mlshell/effects.hpp"

namespace mlshell {

double PenaltyScale::membrane_stiffness_of(const MaterialSpec& material) {
  double Y = 0.0;
  if (const auto* c = std::get_if<ClydeMaterial>(&material.model))
    Y = std::max(c->k[0], c->k[2]);
  else if (const auto* v = std::get_if<SvkMaterial>(&material.model))
    Y = v->youngs_modulus / (1.0 - v->poisson_ratio * v->poisson_ratio);
  else if (const auto* t = std::get_if<TriangleMaterial>(&material.model))
    Y = t->youngs_modulus / (1.0 - t->poisson_ratio * t->poisson_ratio);
  return Y * material.thickness;
}

PenaltyScale PenaltyScale::of(const MaterialSpec& material, const SubdivisionDiscretization& disc,
                              const ParallelLayout& layout) {
  PenaltyScale s;
  s.membrane_stiffness = membrane_stiffness_of(material);
  // The reference limit surface at the corners of every element (ghost faces are not elements),
  // each rank the elements it owns.
  std::vector<SurfacePoint> corners;
  for (int f : disc.elements())
    if (layout.face_owner(f) == layout.rank())
      for (double u : {0.0, 1.0})
        for (double v : {0.0, 1.0}) corners.push_back({f, u, v});
  Point3 lo = Point3::Constant(INFINITY), hi = Point3::Constant(-INFINITY);
  for (const PointBasis& b : disc.evaluator().evaluate(corners, BasisSlots::kValueOnly)) {
    const Point3 x = b.apply(kValue, disc.mesh().points);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), 3, MPI_DOUBLE, MPI_MIN, layout.comm());
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), 3, MPI_DOUBLE, MPI_MAX, layout.comm());
  s.length = (hi - lo).maxCoeff();
  return s;
}

double penalty_parameter(std::optional<double> penalty, double sigma, double mesh_size,
                         const PenaltyScale& scale) {
  if (penalty) return *penalty;
  const double L = scale.length;
  return scale.membrane_stiffness / kPaperMembraneStiffness / L * std::pow(mesh_size / L, -sigma);
}

namespace {

/// A point of the reference surface with its basis on local nodes.
struct LocalPoint {
  std::vector<PetscInt> nodes;
  PointBasis basis;
  Point3 x, xu, xv;  ///< X(ξ) and its tangents
};

LocalPoint local_point(const SubdivisionDiscretization& disc, const ParallelLayout& layout,
                       const SurfacePoint& p) {
  LocalPoint lp;
  lp.basis = disc.evaluator().evaluate({p})[0];
  lp.nodes = to_local_nodes(layout, lp.basis.nodes.data(), lp.basis.size());
  lp.x = lp.basis.apply(kValue, disc.mesh().points);
  lp.xu = lp.basis.apply(kDu, disc.mesh().points);
  lp.xv = lp.basis.apply(kDv, disc.mesh().points);
  return lp;
}

/// Gauss points on this rank's selected boundary edges: the point, its arc-length weight, the
/// in-plane conormal derivative weights (∂_ν N_i) and the unit conormal ν = ∂_ν X itself.
struct EdgeSample {
  LocalPoint point;
  double weight;
  std::vector<double> conormal;
  Point3 conormal_direction = Point3::Zero();
};

std::vector<EdgeSample> edge_samples(const SubdivisionDiscretization& disc,
                                     const ParallelLayout& layout,
                                     const std::vector<BoundaryEdge>& edges) {
  std::vector<EdgeSample> out;
  const GaussRule& rule = disc.gauss();
  for (const BoundaryEdge& e : edges) {
    if (layout.face_owner(e.face) != layout.rank()) continue;
    for (size_t g = 0; g < rule.points.size(); ++g) {
      EdgeSample s{local_point(disc, layout, disc.edge_point(e, rule.points[g])), 0.0, {}, {}};
      const Point3 tangent = (e.edge % 2 == 0) ? s.point.xu : s.point.xv;
      s.weight = rule.weights[g] * tangent.norm();
      // ∂_ν = (ν·A¹) ∂_u + (ν·A²) ∂_v with ν ⊥ tangent in the tangent plane.
      const Point3 n = s.point.xu.cross(s.point.xv).normalized();
      const Point3 nu = tangent.cross(n).normalized();
      Eigen::Matrix2d metric;
      metric << s.point.xu.dot(s.point.xu), s.point.xu.dot(s.point.xv), s.point.xu.dot(s.point.xv),
          s.point.xv.dot(s.point.xv);
      const Eigen::Vector2d c =
          metric.inverse() * Eigen::Vector2d(nu.dot(s.point.xu), nu.dot(s.point.xv));
      for (int i = 0; i < s.point.basis.size(); ++i)
        s.conormal.push_back(c[0] * s.point.basis.w[kDu][i] + c[1] * s.point.basis.w[kDv][i]);
      // Σ ∂_ν N_i X_i = c₀ X_u + c₁ X_v = ν (ν lies in the tangent plane).
      s.conormal_direction = c[0] * s.point.xu + c[1] * s.point.xv;
      out.push_back(std::move(s));
    }
  }
  return out;
}

/// Local force array of an area load with density `f` (N/m²) over this rank's elements.
std::vector<double> area_force(const SubdivisionDiscretization& disc, const ParallelLayout& layout,
                               const Vec3& f) {
  std::vector<double> force(3 * layout.num_local_points(), 0.0);
  for (int face : layout.local_elements()) {
    const ElementBasis b = disc.element_basis(face);
    const auto nodes = to_local_nodes(layout, b.nodes, b.size);
    for (int g = 0; g < disc.num_quadrature_points(); ++g) {
      const double w = disc.quadrature_weight(g) * reference_area(b, g, disc.mesh().points);
      const double* N = b.slot(g, kValue);
      for (int i = 0; i < b.size; ++i)
        for (int c = 0; c < 3; ++c) force[3 * nodes[i] + c] += w * N[i] * f[c];
    }
  }
  return force;
}

SurfacePoint resolve_point(const SubdivisionDiscretization& disc, const Where& where,
                           const CageFrame& frame) {
  return select_point(disc, std::get<PointSelection>(where.selection), frame, where.text);
}

}  // namespace

void add_effect_terms(const Scene& scene, LevelProblem& problem, const std::string& where,
                      const std::function<void(const Effect&, const std::string&)>& build) {
  for (size_t index = 0; index < scene.effects.size(); ++index) {
    const Effect& effect = scene.effects[index];
    const std::string name = effect_name(effect);
    const size_t first_new = problem.terms().size();
    try {
      build(effect, name);
    } catch (const SceneError& e) {
      throw SceneError(scene.file.string() + ": effects[" + std::to_string(index) + "]." + name +
                       where + ": " + e.what());
    }
    for (size_t t = first_new; t < problem.terms().size(); ++t)
      problem.terms()[t]->set_effect_index(static_cast<int>(index));
  }
}

PrescribedMotion motion_function(const std::optional<Motion>& m) {
  if (!m) return [](double) { return RigidPlacement{}; };
  Motion motion = *m;
  return [motion](double t) {
    RigidPlacement placement;
    const Mat3 R = motion.rotation(t);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) placement.rotation(i, j) = R[i][j];
    if (motion.rotate) placement.center = Eigen::Vector3d(motion.rotate->center.data());
    const Vec3 T = motion.at(t);
    placement.translation = Eigen::Vector3d(T.data());
    return placement;
  };
}

namespace {

std::unique_ptr<EnergyTerm> penalty_term(const std::string& name,
                                         const SubdivisionDiscretization& disc,
                                         const ParallelLayout& layout, const Where& where,
                                         const CageFrame& frame, double beta, double beta_rot,
                                         bool clamp, std::array<bool, 3> components,
                                         const std::optional<Motion>& motion) {
  std::vector<PenaltySample> samples;
  if (const auto* curve = std::get_if<CurveSelection>(&where.selection)) {
    for (EdgeSample& s :
         edge_samples(disc, layout, select_curve(disc, *curve, frame, where.text))) {
      PenaltySample p{s.point.nodes, s.point.basis.w[kValue], {}, beta * s.weight, 0.0};
      p.reference = s.point.x;
      if (clamp) {
        p.conormal = s.conormal, p.rotation_weight = beta_rot * s.weight;
        p.reference_conormal = s.conormal_direction;
      }
      samples.push_back(std::move(p));
    }
  } else {
    const SurfacePoint sp = resolve_point(disc, where, frame);
    if (layout.face_owner(sp.face) == layout.rank()) {
      LocalPoint lp = local_point(disc, layout, sp);
      samples.push_back({lp.nodes, lp.basis.w[kValue], {}, beta, 0.0, lp.x});
    }
  }
  return std::make_unique<PenaltyTerm>(name, std::move(samples), components,
                                       motion_function(motion));
}

}  // namespace

std::unique_ptr<LevelProblem> build_level_problem(const Scene& scene,
                                                  const SubdivisionDiscretization& disc,
                                                  const ParallelLayout& layout,
                                                  const CageFrame& frame, double penalty_mesh_size,
                                                  const PenaltyScale* penalty_scale) {
  auto problem = std::make_unique<LevelProblem>(layout);
  problem->add_term(std::make_unique<ShellElasticTerm>(disc, layout, scene.material));
  const double ramp_time = scene.time.dt * scene.time.steps;
  const double h = penalty_mesh_size > 0.0 ? penalty_mesh_size : disc.mesh_size();
  const PenaltyScale scale =
      penalty_scale ? *penalty_scale : PenaltyScale::of(scene.material, disc, layout);
  const int nlocal = layout.num_local_points();
  if (scene.time.quasistatic())
    problem->add_term(std::make_unique<InertiaTerm>(disc, layout, scene.material.density,
                                                    scene.time.proximal_step, "proximal"));
  add_effect_terms(scene, *problem, ".where", [&](const Effect& effect, const std::string& name) {
    if (std::holds_alternative<InertiaEffect>(effect)) {
      problem->add_term(
          std::make_unique<InertiaTerm>(disc, layout, scene.material.density, scene.time.dt));
    } else if (const auto* g = std::get_if<GravityEffect>(&effect)) {
      const double rho = scene.material.density;
      const Vec3 f{rho * g->acceleration[0], rho * g->acceleration[1], rho * g->acceleration[2]};
      problem->add_term(std::make_unique<LinearLoadTerm>(name, area_force(disc, layout, f), 0.0));
    } else if (const auto* s = std::get_if<SurfaceLoadEffect>(&effect)) {
      problem->add_term(std::make_unique<LinearLoadTerm>(
          name, area_force(disc, layout, s->force_per_area), s->ramp ? ramp_time : 0.0));
    } else if (const auto* l = std::get_if<LineLoadEffect>(&effect)) {
      std::vector<double> force(3 * nlocal, 0.0);
      const auto edges =
          select_curve(disc, std::get<CurveSelection>(l->where.selection), frame, l->where.text);
      for (const EdgeSample& s : edge_samples(disc, layout, edges))
        for (int i = 0; i < s.point.basis.size(); ++i)
          for (int c = 0; c < 3; ++c)
            force[3 * s.point.nodes[i] + c] +=
                s.weight * s.point.basis.w[kValue][i] * l->force_per_length[c];
      problem->add_term(
          std::make_unique<LinearLoadTerm>(name, std::move(force), l->ramp ? ramp_time : 0.0));
    } else if (const auto* p = std::get_if<PointLoadEffect>(&effect)) {
      std::vector<double> force(3 * nlocal, 0.0);
      const SurfacePoint sp = resolve_point(disc, p->where, frame);
      if (layout.face_owner(sp.face) == layout.rank()) {
        const LocalPoint lp = local_point(disc, layout, sp);
        for (int i = 0; i < lp.basis.size(); ++i)
          for (int c = 0; c < 3; ++c)
            force[3 * lp.nodes[i] + c] += lp.basis.w[kValue][i] * p->force[c];
      }
      problem->add_term(
          std::make_unique<LinearLoadTerm>(name, std::move(force), p->ramp ? ramp_time : 0.0));
    } else if (const auto* d = std::get_if<DirichletEffect>(&effect)) {
      const double beta = penalty_parameter(d->penalty, d->sigma, h, scale);
      auto term = penalty_term(name, disc, layout, d->where, frame, beta, 0.0, false, d->components,
                               d->motion);
      if (d->tolerance) static_cast<PenaltyTerm&>(*term).enable_augmented_lagrangian(*d->tolerance);
      problem->add_term(std::move(term));
    } else if (const auto* c = std::get_if<ClampEffect>(&effect)) {
      const double beta = penalty_parameter(c->penalty, c->sigma, h, scale);
      const double beta_rot = c->rotation_penalty ? *c->rotation_penalty : beta * h * h;
      problem->add_term(penalty_term(name, disc, layout, c->where, frame, beta, beta_rot, true,
                                     {true, true, true}, c->motion));
    }
  });
  return problem;
}

}  // namespace mlshell
