// Each energy term on its own: finite-difference checks of its gradient and Hessian with a
// tolerance scaled to that term's own magnitude (so that a small term cannot hide behind the
// elastic one), and closed-form values of the inertia and load terms under a rigid translation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

struct TermValue {
  double f = 0, magnitude = 0;
  std::vector<double> g;
};

TermValue evaluate(const EnergyTerm& term, const std::vector<double>& u) {
  CompensatedSum e;
  TermValue out;
  out.g.assign(u.size(), 0.0);
  PetscCallAbort(PETSC_COMM_SELF, term.add(u, e, &out.g, nullptr));
  out.f = e.value();
  out.magnitude = e.magnitude();
  return out;
}

/// H_term d (local, one rank: local and global indices coincide).
std::vector<double> hessian_action(const TestProblem& tp, const EnergyTerm& term,
                                   const std::vector<double>& u, const std::vector<double>& d) {
  Mat H;
  Vec dv, hd;
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->create_matrix(&H));
  // The element-stencil pattern, as the elastic term (always first) leaves it in LevelProblem's
  // Hessian: the constant Hessians are added into that pattern.
  CompensatedSum ignored;
  PetscCallAbort(PETSC_COMM_SELF, tp.problem->terms().front()->add(u, ignored, nullptr, H));
  MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY);
  MatZeroEntries(H);
  PetscCallAbort(PETSC_COMM_SELF, term.add(u, ignored, nullptr, H));
  MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY);
  PetscCallAbort(PETSC_COMM_SELF, term.add_constant_hessian(H));
  MatCreateVecs(H, &dv, &hd);
  for (PetscInt i = 0; i < static_cast<PetscInt>(d.size()); ++i)
    VecSetValue(dv, i, d[i], INSERT_VALUES);
  VecAssemblyBegin(dv);
  VecAssemblyEnd(dv);
  MatMult(H, dv, hd);
  std::vector<double> out(d.size());
  const PetscScalar* a;
  VecGetArrayRead(hd, &a);
  std::copy(a, a + d.size(), out.begin());
  VecRestoreArrayRead(hd, &a);
  VecDestroy(&dv);
  VecDestroy(&hd);
  MatDestroy(&H);
  return out;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

double norm(const std::vector<double>& a) { return std::sqrt(dot(a, a)); }

std::vector<double> local(const TestProblem& tp, Vec v) {
  std::vector<double> out;
  PetscCallAbort(PETSC_COMM_SELF, tp.layout->to_local(v, out));
  return out;
}

const EnergyTerm& term_named(const TestProblem& tp, const std::string& name) {
  for (const auto& t : tp.problem->terms())
    if (t->name() == name) return *t;
  ADD_FAILURE() << "no term '" << name << "'";
  return *tp.problem->terms().front();
}

}  // namespace

TEST(EnergyTerms, EachTermsDerivativesMatchFiniteDifferencesOnItsOwnScale) {
  TestProblem tp("all", PETSC_COMM_SELF);
  Vec uv, dv;
  tp.layout->create_vector(&uv);
  VecDuplicate(uv, &dv);
  tp.random_state(uv, 1e-3, 21);
  tp.random_state(dv, 1.0, 22);
  const std::vector<double> u = local(tp, uv), d = local(tp, dv);
  VecDestroy(&uv);
  VecDestroy(&dv);
  const double h = 1e-6, eps = std::numeric_limits<double>::epsilon();
  std::vector<std::string> seen;
  for (const auto& term : tp.problem->terms()) {
    const std::string& name = term->name();
    seen.push_back(name);
    std::vector<double> up = u, um = u;
    for (size_t i = 0; i < u.size(); ++i) {
      up[i] += h * d[i];
      um[i] -= h * d[i];
    }
    const TermValue at = evaluate(*term, u), plus = evaluate(*term, up),
                    minus = evaluate(*term, um);
    const double gd = dot(at.g, d), fd = (plus.f - minus.f) / (2 * h);
    // Central differences: truncation O(h²) relative to this term's slope, and the round-off of
    // this term's own energy sum divided by h.
    const double roundoff =
        16 * eps * std::max({at.magnitude, plus.magnitude, minus.magnitude}) / h;
    EXPECT_NEAR(gd, fd, 1e-7 * norm(at.g) * norm(d) + roundoff) << name;
    EXPECT_GT(norm(at.g), 0.0) << name << ": a zero gradient checks nothing";
    std::vector<double> column(u.size());
    for (size_t i = 0; i < u.size(); ++i) column[i] = (plus.g[i] - minus.g[i]) / (2 * h);
    const std::vector<double> Hd = hessian_action(tp, *term, u, d);
    std::vector<double> diff(u.size());
    for (size_t i = 0; i < u.size(); ++i) diff[i] = Hd[i] - column[i];
    EXPECT_LE(norm(diff), 1e-6 * norm(Hd) + 16 * eps * norm(at.g) / h * std::sqrt(u.size()))
        << name;
    const bool linear = name == "gravity" || name.find("load") != std::string::npos;
    if (linear)
      EXPECT_EQ(norm(Hd), 0.0) << name << ": a dead load has no Hessian";
    else
      EXPECT_GT(norm(Hd), 1e-3 * norm(at.g)) << name << ": the Hessian action is missing";
  }
  // Every kind of term of the scene was checked.
  for (const char* expected :
       {"inertia", "gravity", "surface_load", "line_load", "point_load", "dirichlet", "clamp"})
    EXPECT_NE(std::find(seen.begin(), seen.end(), expected), seen.end()) << expected;
}

// Catmull–Clark is affine invariant: moving every control point by a rigid motion moves the
// limit surface by it. A support whose motion is that rigid motion then costs nothing, its
// points and (for the clamp) its slope across the boundary both turned, and costs something
// halfway through the motion or without it.
TEST(EnergyTerms, SupportsCostNothingAlongTheirOwnRigidMotions) {
  TestProblem tp("all", PETSC_COMM_SELF);
  tp.problem->set_time(2.0);  // the motions are complete
  const int n = tp.layout->num_local_points();
  std::vector<double> X(3 * n);
  ASSERT_EQ(3 * tp.disc->mesh().points.size(), static_cast<size_t>(tp.disc->num_dofs()));
  {
    Vec x;
    tp.layout->create_vector(&x);
    std::vector<double> natural;
    if (tp.layout->rank() == 0)
      for (const Point3& p : tp.disc->mesh().points)
        for (int c = 0; c < 3; ++c) natural.push_back(p[c]);
    tp.layout->scatter_natural(natural, x);
    X = local(tp, x);
    VecDestroy(&x);
  }
  for (const auto& [index, name] : {std::pair<size_t, const char*>{5, "dirichlet"},
                                    std::pair<size_t, const char*>{7, "clamp"}}) {
    SCOPED_TRACE(name);
    const auto& effect = tp.scene.effects[index];
    const Motion& motion = std::holds_alternative<DirichletEffect>(effect)
                               ? *std::get<DirichletEffect>(effect).motion
                               : *std::get<ClampEffect>(effect).motion;
    ASSERT_TRUE(motion.rotate);
    // The full motion, written out: R(θ)(X − c) + c + T − X.
    const Eigen::Vector3d axis(motion.rotate->axis.data()), c(motion.rotate->center.data()),
        T(motion.translate.data());
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(motion.rotate->angle, axis.normalized()).toRotationMatrix();
    std::vector<double> u(3 * n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d Xi(X[3 * i], X[3 * i + 1], X[3 * i + 2]);
      const Eigen::Vector3d d = R * (Xi - c) + c + T - Xi;
      for (int k = 0; k < 3; ++k) u[3 * i + k] = d[k];
    }
    const EnergyTerm& term = *tp.problem->terms()[index + 1];  // after the elastic term
    ASSERT_EQ(term.name(), name);
    EXPECT_NEAR(evaluate(term, u).f, 0.0, 1e-18);
    tp.problem->set_time(1.0);  // halfway: the full turn is too far
    EXPECT_GT(evaluate(term, u).f, 1e-3);
    tp.problem->set_time(2.0);
  }
}

// A rigid translation t of every control point translates the limit surface by t (Catmull–Clark
// is affine invariant). On the unit square (area 1, right edge of length 1) each term then has a
// closed-form value, with s = min(1, time / (dt · steps)) for ramped loads.
TEST(EnergyTerms, InertiaAndLoadsHaveTheirClosedFormValuesUnderATranslation) {
  TestProblem tp("all", PETSC_COMM_SELF);
  const double rho = 0.4, dt = 0.5, ramp_time = 0.5 * 4, time = 1.0;  // TestProblem's scene
  const double s = time / ramp_time;
  const double t[3] = {0.03, -0.02, 0.05};
  auto* inertia = tp.problem->find_term<InertiaTerm>();
  ASSERT_NE(inertia, nullptr);
  const int n = tp.layout->num_local_points();
  inertia->set_predictor(std::vector<double>(3 * n, 0.0));
  std::vector<double> u(3 * n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) u[3 * i + c] = t[c];
  auto along = [&](const double* f) { return f[0] * t[0] + f[1] * t[1] + f[2] * t[2]; };
  const double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
  const double gravity[3] = {0, 0, -9.81 * rho}, surface[3] = {0.1, 0.0, -3.0},
               line[3] = {0, 0.5, -4}, point[3] = {0, 0, -1};
  struct Expected {
    const char* name;
    double value;
  };
  for (const Expected& e :
       {Expected{"inertia", rho / (2 * dt * dt) * tt}, Expected{"gravity", -along(gravity)},
        Expected{"surface_load", -s * along(surface)},  // ramped
        Expected{"line_load", -along(line)},            // not ramped
        Expected{"point_load", -s * along(point)}}) {   // ramped
    const double value = evaluate(term_named(tp, e.name), u).f;
    EXPECT_NEAR(value, e.value, 1e-10 * std::abs(e.value)) << e.name;
  }
  // Ramped loads follow the time: none at t = 0, full from t = dt · steps on.
  for (const double when : {0.0, ramp_time, 2 * ramp_time}) {
    tp.problem->set_time(when);
    const double scale = std::min(1.0, when / ramp_time);
    EXPECT_NEAR(evaluate(term_named(tp, "surface_load"), u).f, -scale * along(surface), 1e-12)
        << "time " << when;
    EXPECT_NEAR(evaluate(term_named(tp, "line_load"), u).f, -along(line), 1e-12) << when;
  }
}
