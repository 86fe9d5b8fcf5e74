// Each implicit integrator on the spinning neo-Hookean cube (a coarse cube
// mesh, n = 2) to t = 20: energy and angular momentum behave as the method
// promises.
#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/energy_momentum.h>
#include <estep/implicit/ida_bdf.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

#include <iomanip>
#include <sstream>
#include <string>

namespace
{
  using estep_test::counter;

  std::string
  text(const double x)
  {
    std::ostringstream s;
    s << std::setprecision(4) << x;
    return s.str();
  }

  /** Record the figures of a run in the test's XML output. */
  void
  record(const estep_test::CubeRun &run)
  {
    testing::Test::RecordProperty("energy_drift", text(run.energy_drift));
    testing::Test::RecordProperty("momentum_drift", text(run.momentum_drift));
    testing::Test::RecordProperty("E0", text(run.E0));
    testing::Test::RecordProperty("E_end", text(run.E_end));
    for (const auto &c : run.counters)
      testing::Test::RecordProperty(c.first, std::to_string(c.second));
  }

  const estep::ElasticBodyWithHessian &
  coarse_cube()
  {
    static const auto body = estep_test::cube_with_hessian(2);
    return *body;
  }

  TEST(SpinningCube, ArkodeMidpointConservesMomentumEnergyBounded)
  {
    estep::ImplicitParameters parameters;
    parameters.newton_tolerance = 1e-10;
    estep::ArkodeRungeKutta integrator(
      coarse_cube(),
      parameters,
      estep::ArkodeRungeKutta::Method::midpoint,
      0.05);
    const auto run = estep_test::run_cube(coarse_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_EQ(integrator.n_steps(), 400u);
    EXPECT_LT(run.momentum_drift, 1e-8);
    EXPECT_LT(run.energy_drift, 1e-2);
  }

  TEST(SpinningCube, EnergyMomentumConservesEnergyAndMomentum)
  {
    estep::ImplicitParameters parameters;
    parameters.newton_tolerance = 1e-10;
    estep::EnergyMomentum integrator(coarse_cube(), parameters, 0.05);
    const auto run = estep_test::run_cube(coarse_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_EQ(integrator.n_steps(), 400u);
    EXPECT_LT(run.momentum_drift, 1e-8);
    EXPECT_LT(run.energy_drift, 1e-8);
  }

  TEST(SpinningCube, IdaBdfDissipatesEnergyConservesMomentum)
  {
    estep::ImplicitParameters parameters;
    parameters.relative_tolerance = 1e-6;
    parameters.absolute_tolerance = 1e-8;
    estep::IdaBdf integrator(coarse_cube(), parameters, 1e-3);
    const auto    run = estep_test::run_cube(coarse_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.E_end, run.E0);
    EXPECT_LT(run.momentum_drift, 1e-3);
  }

  TEST(SpinningCube, ArkodeDirkAdaptive)
  {
    estep::ImplicitParameters parameters;
    parameters.relative_tolerance = 1e-6;
    parameters.absolute_tolerance = 1e-8;
    estep::ArkodeRungeKutta integrator(coarse_cube(),
                                       parameters,
                                       estep::ArkodeRungeKutta::Method::dirk,
                                       1e-3);
    const auto run = estep_test::run_cube(coarse_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.E_end, run.E0);
    EXPECT_LT(run.momentum_drift, 1e-3);
  }
} // namespace
