// The scene's energy scale (the energy floor's S) and the causes a failed step names
// (step_failure.hpp).
#include "mlshell/step_failure.hpp"

#include <gtest/gtest.h>

#include "mlshell/step_solver.hpp"

namespace mlshell {
namespace {

/// A balloon: a closed neo-Hookean sphere under pressure, quasistatic, no ramp.
Scene balloon(double pressure) {
  Scene s;
  TriangleMaterial m;
  m.youngs_modulus = 1e6;
  m.poisson_ratio = 0.45;
  s.material.model = m;
  s.material.thickness = 5e-4;
  s.material.density = 0.55;
  s.effects.push_back(PressureEffect{pressure, false});
  s.time.integrator = TimeSpec::Integrator::kQuasistatic;
  return s;
}

TEST(EnergyScale, IsTheMembraneEnergyOfUnitStrainPlusTheLoadsWorkOverTheSize) {
  const double area = 0.125, size = 0.35;
  const EnergyScale s = energy_scale(balloon(1e5), area, size);
  EXPECT_DOUBLE_EQ(s.elastic, 1e6 * 5e-4 * area);
  EXPECT_DOUBLE_EQ(s.pressure, 1e5 * area * size);
  EXPECT_EQ(s.loads, 0.0);
  EXPECT_NE(s.describe().find("pressure p*A*l"), std::string::npos) << s.describe();
  EXPECT_EQ(s.describe().find("loads"), std::string::npos) << s.describe();
}

TEST(EnergyScale, ChangesWithTheUnitsAsAnEnergyDoes) {
  // The same scene in millimetres (N, mm, MPa = N/mm²): energies in N mm = 1e-3 J.
  Scene si = balloon(1e5);
  si.effects.push_back(GravityEffect{{0, 0, -9.81}});
  si.effects.push_back(PointLoadEffect{{}, {0, 3.0, 4.0}, false});
  Scene mm = si;
  std::get<TriangleMaterial>(mm.material.model).youngs_modulus = 1.0;  // MPa
  mm.material.thickness = 0.5;
  mm.material.density = 0.55e-9;  // t/mm² (N = t mm/s²)
  std::get<GravityEffect>(mm.effects[1]).acceleration = {0, 0, -9810.0};
  std::get<PressureEffect>(mm.effects[0]).pressure = 0.1;
  const double area = 0.125, size = 0.35;
  const double s_si = energy_scale(si, area, size).total();
  const double s_mm = energy_scale(mm, area * 1e6, size * 1e3).total();
  EXPECT_NEAR(s_mm, 1e3 * s_si, 1e-9 * s_mm);
}

TEST(EnergyScale, CountsTheDistanceMotionsAndFreeFlightCarryLoads) {
  Scene s = balloon(0.0);
  s.effects.clear();
  s.effects.push_back(GravityEffect{{0, 0, -10.0}});
  const double area = 2.0, size = 1.5, weight = 0.55 * 10.0 * area;
  EXPECT_DOUBLE_EQ(energy_scale(s, area, size).loads, weight * size);
  DirichletEffect d;
  d.motion = Motion{{0, 0, 4.0}, {0.0, 1.0}};
  s.effects.push_back(d);
  EXPECT_DOUBLE_EQ(energy_scale(s, area, size).loads, weight * (size + 4.0));
  s.effects.pop_back();
  s.effects.push_back(InertiaEffect{});
  s.time = TimeSpec{};  // implicit Euler
  s.time.dt = 0.1;
  s.time.steps = 20;  // T = 2 s: a free fall of ½ g T² = 20 m
  EXPECT_DOUBLE_EQ(energy_scale(s, area, size).loads, weight * (size + 20.0));
}

TEST(EnergyFloor, StopsOnlyBelowTheStartLessTheBound) {
  StepSolver::EnergyFloor floor;
  floor.scale = 10.0;  // B = 1e6 (10 + |f₀|)
  EXPECT_FALSE(floor.below(-2.0));  // f₀ = -2: B = 1.2e7
  EXPECT_FALSE(floor.below(-1.2e7));
  floor.observe(-1.3e7);  // a trial point: noted, stops nothing
  EXPECT_TRUE(floor.trial_crossed);
  EXPECT_FALSE(floor.crossed);
  EXPECT_DOUBLE_EQ(floor.bound(), kUnboundedEnergyFactor * 12.0);
  EXPECT_TRUE(floor.below(-1.3e7));
  EXPECT_TRUE(floor.crossed);
  StepSolver::EnergyFloor none;  // no scale: no floor
  EXPECT_FALSE(none.below(0.0));
  EXPECT_FALSE(none.below(-1e300));
}

TEST(StepFailure, NamesOnlyWhatTheSceneHas) {
  // A quasistatic balloon without ramps: the pressure, no step size (dt changes nothing).
  const std::string causes = unbounded_energy_causes(balloon(1e5));
  EXPECT_NE(causes.find("pressure (100000 Pa) may exceed"), std::string::npos) << causes;
  EXPECT_NE(causes.find("`ramp: true`"), std::string::npos) << causes;
  EXPECT_EQ(causes.find("dt"), std::string::npos) << causes;
  EXPECT_EQ(causes.find("nothing holds"), std::string::npos) << causes;
  const std::string remedies = not_converged_remedies(balloon(1e5), false);
  EXPECT_EQ(remedies.find("dt"), std::string::npos) << remedies;
  EXPECT_NE(remedies.find("-tao_max_it) or another solver (-tao_type)."), std::string::npos)
      << remedies;
  EXPECT_NE(not_converged_remedies(balloon(1e5), true).find("-snes_max_it"), std::string::npos);

  // Ramped: smaller load steps.
  Scene ramped = balloon(1e5);
  std::get<PressureEffect>(ramped.effects[0]).ramp = true;
  EXPECT_NE(unbounded_energy_causes(ramped).find("smaller load steps"), std::string::npos);
  EXPECT_NE(not_converged_remedies(ramped, false).find("or smaller load steps"),
            std::string::npos);

  // Loads without supports or inertia: nothing holds the shell; with a clamp it is held.
  Scene free = balloon(0.0);
  free.effects = {GravityEffect{}, PointLoadEffect{}};
  const std::string held_by_nothing = unbounded_energy_causes(free);
  EXPECT_NE(held_by_nothing.find("nothing holds the shell against its loads (gravity, "
                                 "point_load)"),
            std::string::npos)
      << held_by_nothing;
  EXPECT_EQ(held_by_nothing.find("pressure"), std::string::npos) << held_by_nothing;
  free.effects.push_back(ClampEffect{});
  EXPECT_EQ(unbounded_energy_causes(free).find("nothing holds"), std::string::npos);

  // Inertia: dt matters; denim-table1's well is named.
  Scene dynamic = balloon(0.0);
  dynamic.effects = {InertiaEffect{}, GravityEffect{}};
  dynamic.time = TimeSpec{};
  dynamic.material.preset = "denim-table1";
  const std::string d = unbounded_energy_causes(dynamic);
  EXPECT_NE(d.find("a smaller dt"), std::string::npos) << d;
  EXPECT_NE(d.find("denim-table1 has a negative-energy well"), std::string::npos) << d;
  EXPECT_EQ(d.find("nothing holds"), std::string::npos) << d;
  EXPECT_NE(not_converged_remedies(dynamic, false).find("or a smaller dt"), std::string::npos);

  // Nothing to name: a fallback, never an empty list.
  Scene plain = balloon(0.0);
  plain.effects.clear();
  EXPECT_NE(unbounded_energy_causes(plain).find("check the loads and boundary conditions"),
            std::string::npos);
}

}  // namespace
}  // namespace mlshell
