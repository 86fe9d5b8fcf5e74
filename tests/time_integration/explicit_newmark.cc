// Explicit Newmark (velocity Verlet): second order on the argon cluster and
// against the exact motion of coupled harmonic oscillators, and a blow-up that
// ends with status unstable.
#include <estep/time_integration/explicit_newmark.h>
#include <estep/time_integration/time_loop.h>

#include <gtest/gtest.h>

#include "../fitted_slope.h"
#include "argon.h"
#include "harmonic_oscillator.h"

#include <cmath>
#include <vector>

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
  /** A span that is a whole number of steps takes exactly that number: the
   * round-off that the sum of the steps accumulates stretches the last one a
   * little instead of adding a step of round-off length. */
  TEST(ExplicitNewmark, WholeNumberOfStepsLeavesNoRoundOffStep)
  {
    const Problem   argon = estep::testing::argon_cluster();
    ExplicitNewmark newmark(*argon.system, 0.0125);
    newmark.initialize(0., argon.q0, argon.v0);
    TimeLoopSettings settings;
    settings.end_time           = 10.;
    settings.output_interval    = 0.1;
    const TimeLoopResult result = run_time_loop(newmark, settings, {});
    ASSERT_EQ(result.status, RunStatus::completed);
    EXPECT_EQ(newmark.n_steps(), 800u);
    EXPECT_GT(newmark.min_step(), 0.0125 * (1. - 1e-6));
    EXPECT_LT(newmark.max_step(), 0.0125 * (1. + 1e-6));
    EXPECT_EQ(newmark.time(), 10.);
  }

  /** The closed-form motion of the oscillator solves M q'' = -K q. */
  TEST(HarmonicOscillator, ExactStateSolvesTheEquationsOfMotion)
  {
    const estep::testing::HarmonicOscillator oscillator;
    Vector                                   q0, v0, q, v, qp, vp, qm, vm;
    estep::testing::HarmonicOscillator::initial_state(q0, v0);
    oscillator.exact_state(0., q0, v0, q, v);
    for (unsigned int i = 0; i < 2; ++i)
      {
        EXPECT_NEAR(q[i], q0[i], 1e-15);
        EXPECT_NEAR(v[i], v0[i], 1e-15);
      }
    const double E0 = oscillator.total_energy(q0, v0);
    const double h  = 1e-4;
    for (const double t : {0.7, 3.1, 9.5})
      {
        oscillator.exact_state(t, q0, v0, q, v);
        oscillator.exact_state(t + h, q0, v0, qp, vp);
        oscillator.exact_state(t - h, q0, v0, qm, vm);
        Vector g;
        oscillator.gradient(q, g);
        for (unsigned int i = 0; i < 2; ++i)
          {
            EXPECT_NEAR((qp[i] - qm[i]) / (2. * h), v[i], 1e-7);
            EXPECT_NEAR((vp[i] - vm[i]) / (2. * h),
                        -oscillator.inverse_mass()[i] * g[i],
                        1e-7);
          }
        EXPECT_NEAR(oscillator.total_energy(q, v), E0, 1e-14);
      }
  }

  /** Kinetic energy and momenta weigh each coordinate with its own mass. */
  TEST(HarmonicOscillator, KineticEnergyAndMomentaUseTheMasses)
  {
    const estep::testing::HarmonicOscillator oscillator;
    Vector                                   q(2), v(2);
    q[0] = 0.7, q[1] = -0.4;
    v[0] = 0.3, v[1] = 1.1;
    const double p[2] = {oscillator.mass[0] * v[0], oscillator.mass[1] * v[1]};
    EXPECT_NEAR(kinetic_energy(oscillator, v),
                0.5 * (p[0] * v[0] + p[1] * v[1]),
                1e-15);
    const Momenta m = compute_momenta(oscillator, q, v);
    EXPECT_NEAR(m.linear[0], p[0], 1e-15);
    EXPECT_NEAR(m.linear[1], p[1], 1e-15);
    EXPECT_NEAR(m.angular[2], q[0] * p[1] - q[1] * p[0], 1e-15);
  }

  /**
   * Velocity Verlet on the coupled oscillators to t = 10 against the exact
   * motion: the largest error of position and velocity, at the ends of the
   * steps and in dense output between them, falls like dt^2 over three
   * halvings of the step, and the energy error is O(dt^2) both ways (the
   * scheme is symplectic: no drift, an oscillation of relative size about
   * (omega dt)^2 / 8).
   */
  TEST(ExplicitNewmark, IsSecondOrderAgainstTheExactMotion)
  {
    const estep::testing::HarmonicOscillator oscillator;
    Vector                                   q0, v0, q_exact, v_exact;
    estep::testing::HarmonicOscillator::initial_state(q0, v0);
    const double        E0    = oscillator.total_energy(q0, v0);
    const double        t_end = 10.;
    std::vector<double> steps, errors, energy_errors;
    for (const double dt : {0.1, 0.05, 0.025, 0.0125})
      {
        ExplicitNewmark newmark(oscillator, dt);
        newmark.initialize(0., q0, v0);
        double       error = 0., energy_error = 0.;
        const double output_interval = 0.37; // not a multiple of the steps
        double       next_output     = output_interval;
        const auto   compare =
          [&](const double t, const Vector &q, const Vector &v) {
            oscillator.exact_state(t, q0, v0, q_exact, v_exact);
            for (unsigned int i = 0; i < 2; ++i)
              error = std::max({error,
                                std::abs(q[i] - q_exact[i]),
                                std::abs(v[i] - v_exact[i])});
          };
        while (newmark.time() < t_end)
          {
            newmark.step(t_end);
            compare(newmark.time(), newmark.position(), newmark.velocity());
            energy_error =
              std::max(energy_error,
                       std::abs(oscillator.total_energy(newmark.position(),
                                                        newmark.velocity()) -
                                E0) /
                         E0);
            for (; next_output <= newmark.time();
                 next_output += output_interval)
              {
                const Snapshot s = newmark.dense_output(next_output);
                EXPECT_EQ(s.t, next_output);
                compare(next_output, s.q, s.v);
                // The snapshot's energies are the system's.
                EXPECT_NEAR(s.kinetic_energy + s.potential_energy,
                            oscillator.total_energy(s.q, s.v),
                            1e-14);
              }
          }
        EXPECT_EQ(newmark.time(), t_end);
        std::cout << "dt = " << dt << ": error " << error << ", energy error "
                  << energy_error << '\n';
        steps.push_back(dt);
        errors.push_back(error);
        energy_errors.push_back(energy_error);
      }
    const double rate = estep_test::fitted_slope(steps, errors);
    std::cout << "fitted rate " << rate << ", energy error rate "
              << estep_test::fitted_slope(steps, energy_errors) << '\n';
    EXPECT_GT(rate, 1.8);
    EXPECT_LT(rate, 2.2);
    // Second order with a constant of the size of the phase error omega^3
    // t_end / 24 per unit amplitude.
    EXPECT_LT(errors.back(), 2e-3);
    // Bounded both ways: at least the second-order oscillation (a scheme
    // that conserved the energy exactly would be another one), at most twice
    // (omega_max dt)^2 / 8.
    for (unsigned int k = 0; k < steps.size(); ++k)
      {
        const double bound = 2. * 3.5 * steps[k] * steps[k] / 8.;
        EXPECT_LT(energy_errors[k], bound) << "dt = " << steps[k];
        EXPECT_GT(energy_errors[k], 0.02 * bound) << "dt = " << steps[k];
      }
  }
} // namespace
