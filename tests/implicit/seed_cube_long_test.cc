// Each implicit integrator on the spinning cube (n = 8: 12,288 tets)
// to t = 20 (tier "long": minutes). The figures are recorded in the XML
// output (--gtest_output=xml) for doc/implicit_integrators.md.
#include <deal.II/base/mpi.h>

#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/energy_momentum.h>
#include <estep/implicit/ida_bdf.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

#include <iomanip>
#include <sstream>

namespace
{
  const estep::ElasticBodyWithHessian &
  seed_cube()
  {
    static const auto body = estep_test::cube_with_hessian(8);
    return *body;
  }

  void
  record(const estep_test::CubeRun &run)
  {
    const auto text = [](const double x) {
      std::ostringstream s;
      s << std::setprecision(4) << x;
      return s.str();
    };
    testing::Test::RecordProperty("energy_drift", text(run.energy_drift));
    testing::Test::RecordProperty("momentum_drift", text(run.momentum_drift));
    testing::Test::RecordProperty("E0", text(run.E0));
    testing::Test::RecordProperty("E_end", text(run.E_end));
    for (const auto &c : run.counters)
      testing::Test::RecordProperty(c.first, std::to_string(c.second));
  }

  TEST(SeedCube, ArkodeMidpoint)
  {
    estep::ArkodeRungeKutta integrator(
      seed_cube(), {}, estep::ArkodeRungeKutta::Method::midpoint, 0.05);
    const auto run = estep_test::run_cube(seed_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.momentum_drift, 1e-8);
    EXPECT_LT(run.energy_drift, 1e-2);
  }

  TEST(SeedCube, EnergyMomentum)
  {
    estep::EnergyMomentum integrator(seed_cube(), {}, 0.05);
    const auto run = estep_test::run_cube(seed_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.momentum_drift, 1e-8);
    EXPECT_LT(run.energy_drift, 1e-8);
  }

  TEST(SeedCube, IdaBdf)
  {
    estep::IdaBdf integrator(seed_cube(), {}, 1e-3);
    const auto    run = estep_test::run_cube(seed_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.E_end, run.E0);
    EXPECT_LT(run.momentum_drift, 1e-3);
  }

  TEST(SeedCube, ArkodeIrk)
  {
    estep::ArkodeRungeKutta integrator(seed_cube(),
                                       {},
                                       estep::ArkodeRungeKutta::Method::dirk,
                                       1e-3);
    const auto run = estep_test::run_cube(seed_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.momentum_drift, 1e-3);
  }

  TEST(SeedCube, ArkodeMidpointCgAmg)
  {
    estep::ImplicitParameters p;
    p.linear_solver = estep::ImplicitLinearSolver::cg_amg;
    estep::ArkodeRungeKutta integrator(
      seed_cube(), p, estep::ArkodeRungeKutta::Method::midpoint, 0.05);
    const auto run = estep_test::run_cube(seed_cube(), integrator, 20.);
    record(run);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.momentum_drift, 1e-8);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
