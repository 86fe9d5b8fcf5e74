// Explicit Newmark (velocity Verlet): second order on the argon cluster, and a
// blow-up that ends with status unstable.
#include <estep/time_integration/explicit_newmark.h>
#include <estep/time_integration/time_loop.h>

#include <gtest/gtest.h>

#include "argon.h"

#include <cmath>

namespace
{
  using namespace estep;

  Vector
  position_at(const Problem &problem, const double dt, const double t_end)
  {
    ExplicitNewmark newmark(*problem.system, dt);
    newmark.initialize(0., problem.q0, problem.v0);
    while (newmark.time() < t_end)
      newmark.step(t_end);
    return newmark.position();
  }

  TEST(ExplicitNewmark, IsSecondOrderOnTheArgonCluster)
  {
    const Problem argon     = estep::testing::argon_cluster();
    const double  t_end     = 1.;
    const Vector  reference = position_at(argon, 1e-4, t_end);
    double        previous  = 0.;
    for (const double dt : {0.02, 0.01, 0.005})
      {
        Vector error = position_at(argon, dt, t_end);
        error -= reference;
        if (previous > 0.)
          {
            const double rate = std::log2(previous / error.l2_norm());
            std::cout << "dt = " << dt << ": error " << error.l2_norm()
                      << ", rate " << rate << '\n';
            EXPECT_GT(rate, 1.8);
            EXPECT_LT(rate, 2.2);
          }
        previous = error.l2_norm();
      }
  }

  TEST(ExplicitNewmark, ReportsABlowUpAsUnstable)
  {
    const Problem   argon = estep::testing::argon_cluster();
    ExplicitNewmark newmark(*argon.system, 0.5);
    newmark.initialize(0., argon.q0, argon.v0);
    TimeLoopSettings settings;
    settings.end_time           = 100.;
    const TimeLoopResult result = run_time_loop(newmark, settings, {});
    EXPECT_EQ(result.status, RunStatus::unstable);
    EXPECT_NE(result.message.find("unstable"), std::string::npos);
    EXPECT_LT(result.final_time, 100.);
  }

  TEST(ExplicitNewmark, ConservesMomentaAndEndsOnTheEndTime)
  {
    const Problem   argon = estep::testing::argon_cluster();
    ExplicitNewmark newmark(*argon.system, 0.0123);
    newmark.initialize(0., argon.q0, argon.v0);
    while (newmark.time() < 1.)
      newmark.step(1.);
    EXPECT_EQ(newmark.time(), 1.);
    const Momenta m0 = compute_momenta(*argon.system, argon.q0, argon.v0);
    const Momenta m1 =
      compute_momenta(*argon.system, newmark.position(), newmark.velocity());
    EXPECT_NEAR(m1.angular[2], m0.angular[2], 1e-12 * std::abs(m0.angular[2]));
    EXPECT_NEAR(m1.linear[0], m0.linear[0], 1e-12);
  }
} // namespace
