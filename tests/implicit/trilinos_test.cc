// The Trilinos linear solver option (CG + ML AMG) against the direct solver:
// the same midpoint and energy-momentum runs on the coarse spinning cube.
// Trilinos needs MPI: this program initialises it in its own main().
#include <deal.II/base/mpi.h>

#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/energy_momentum.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

namespace
{
  const estep::ElasticBodyWithHessian &
  coarse_cube()
  {
    static const auto body = estep_test::cube_with_hessian(2);
    return *body;
  }

  estep::ImplicitParameters
  cg_amg()
  {
    estep::ImplicitParameters p;
    p.linear_solver    = estep::ImplicitLinearSolver::cg_amg;
    p.linear_tolerance = 1e-12;
    return p;
  }

  TEST(TrilinosCgAmg, MidpointMatchesDirect)
  {
    estep::ArkodeRungeKutta direct(coarse_cube(),
                                   estep::ImplicitParameters(),
                                   estep::ArkodeRungeKutta::Method::midpoint,
                                   0.05);
    estep::ArkodeRungeKutta iterative(coarse_cube(),
                                      cg_amg(),
                                      estep::ArkodeRungeKutta::Method::midpoint,
                                      0.05);
    const auto              a = estep_test::run_cube(coarse_cube(), direct, 5.);
    const auto b = estep_test::run_cube(coarse_cube(), iterative, 5.);
    ASSERT_EQ(b.result.status, estep::RunStatus::completed) << b.result.message;
    EXPECT_LT(b.momentum_drift, 1e-8);
    estep::Vector d = direct.position();
    d -= iterative.position();
    EXPECT_LT(d.linfty_norm(), 1e-7);
    // On this small mesh ML's coarse level is the whole matrix (a direct
    // solve), so CG needs one iteration per solve; at least one per Newton
    // iteration in any case.
    EXPECT_GE(estep_test::counter(b.counters, "linear iterations"),
              estep_test::counter(b.counters, "newton iterations"));
  }

  TEST(TrilinosCgAmg, EnergyMomentumConserves)
  {
    estep::EnergyMomentum integrator(coarse_cube(), cg_amg(), 0.05);
    const auto run = estep_test::run_cube(coarse_cube(), integrator, 5.);
    ASSERT_EQ(run.result.status, estep::RunStatus::completed)
      << run.result.message;
    EXPECT_LT(run.energy_drift, 1e-8);
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
