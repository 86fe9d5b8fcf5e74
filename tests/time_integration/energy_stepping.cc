// Energy-stepping: exact conservation, time reversibility, convergence to the
// exact motion, and no level ever stepped over along a real system's flights.
#include <estep/base/interruption.h>
#include <estep/systems/lennard_jones_cluster.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/time_loop.h>

#include <gtest/gtest.h>

#include "../terrace_audit.h"
#include "argon.h"
#include "test_flights.h"

#include <cmath>
#include <optional>
#include <string>

namespace
{
  using namespace estep;

  double
  relative_difference(const double a, const double b)
  {
    return std::abs(a - b) / std::abs(a);
  }

  TEST(EnergyStepping, ConservesEnergyAndMomentaOverHundredThousandSteps)
  {
    const Problem  argon = estep::testing::argon_cluster();
    const double   h     = 1e-3; // epsilon: about 1e-4 |E0|
    EnergyStepping stepping(*argon.system, h);
    stepping.initialize(0., argon.q0, argon.v0);
    const double  E0 = stepping.terraced_energy();
    const Momenta m0 = compute_momenta(*argon.system, argon.q0, argon.v0);
    ASSERT_GT(std::abs(m0.angular[2]), 0.1);

    double worst_energy = 0., worst_linear = 0., worst_angular = 0.;
    while (stepping.n_steps() < 100000)
      {
        stepping.step(1e6);
        const Momenta m = compute_momenta(*argon.system,
                                          stepping.position(),
                                          stepping.velocity());
        worst_energy =
          std::max(worst_energy,
                   relative_difference(E0, stepping.terraced_energy()));
        worst_linear = std::max({worst_linear,
                                 std::abs(m.linear[0] - m0.linear[0]),
                                 std::abs(m.linear[1] - m0.linear[1])});
        worst_angular =
          std::max(worst_angular,
                   relative_difference(m0.angular[2], m.angular[2]));
        // Stop at the first loss of conservation (a broken jump would
        // otherwise run on through a meaningless trajectory).
        ASSERT_LT(worst_energy, 1e-12) << "at step " << stepping.n_steps();
      }
    const auto counters = stepping.counters();
    std::cout << "after " << stepping.n_steps()
              << " steps (t = " << stepping.time() << "): terraced energy "
              << worst_energy << " relative, linear momentum " << worst_linear
              << " absolute, angular momentum " << worst_angular
              << " relative\n";
    EXPECT_LT(worst_energy, 1e-12);
    EXPECT_LT(worst_linear, 1e-12); // the total momentum is zero
    EXPECT_LT(worst_angular, 1e-12);
    // The true energy stays within one energy step of the terraced one.
    const double V = argon.system->energy(stepping.position());
    EXPECT_LE(std::abs(V - stepping.terrace_index() * h), h * (1. + 1e-9));
  }

  TEST(EnergyStepping, ArgonFlightsStayOnTheirTerrace)
  {
    // V sampled at 64 points inside every flight lies between the flight's
    // two levels, for a coarse and a fine energy step and shifted terraces.
    const Problem argon = estep::testing::argon_cluster();
    for (const auto &[h, offset] :
         {std::pair{1e-2, 0.}, std::pair{1e-3, 0.}, std::pair{1e-3, 0.5}})
      {
        EnergyStepping stepping(*argon.system, h, offset);
        stepping.initialize(0., argon.q0, argon.v0);
        double worst = -1.;
        while (stepping.n_steps() < 20000)
          {
            stepping.step(1e6);
            worst = std::max(worst, estep_test::terrace_excursion(stepping));
            ASSERT_LT(worst, 1e-9) << "at step " << stepping.n_steps();
          }
        std::cout << "h = " << h << ", offset " << offset
                  << ": largest excursion beyond a level " << worst << " h\n";
        EXPECT_LT(worst, 1e-9);
      }
  }

  TEST(EnergyStepping, IsTimeReversible)
  {
    // Forward, flip the velocities, back for as long. The terraced flow is
    // reversible; the computed one is up to round-off, which near-grazing
    // crossings amplify strongly (the jump depends on sqrt(a^2 - 2 h m)), so
    // the horizons are a few hundred to a thousand steps.
    const Problem argon = estep::testing::argon_cluster();
    for (const auto &[h, T] : {std::pair{1e-2, 1.}, std::pair{1e-3, 0.25}})
      {
        EnergyStepping forward(*argon.system, h);
        forward.initialize(0., argon.q0, argon.v0);
        while (forward.time() < T)
          forward.step(T);
        Vector v_back = forward.velocity();
        v_back *= -1.;
        EnergyStepping backward(*argon.system, h);
        backward.initialize(T, forward.position(), v_back);
        EXPECT_EQ(backward.terrace_index(), forward.terrace_index());
        while (backward.time() < 2. * T)
          backward.step(2. * T);

        Vector dq = backward.position(), dv = backward.velocity();
        dq -= argon.q0;
        dv += argon.v0;
        std::cout << "h = " << h << ": " << forward.n_steps()
                  << " steps forward, " << backward.n_steps()
                  << " back: position error "
                  << dq.l2_norm() / argon.q0.l2_norm() << ", velocity error "
                  << dv.l2_norm() / argon.v0.l2_norm() << " (relative)\n";
        EXPECT_GT(forward.n_steps(), 300u);
        EXPECT_EQ(backward.n_steps(), forward.n_steps());
        EXPECT_LT(dq.l2_norm() / argon.q0.l2_norm(), 1e-9);
        EXPECT_LT(dv.l2_norm() / argon.v0.l2_norm(), 1e-9);
      }
  }

  /** An anisotropic harmonic oscillator in the plane, V = (k1 x^2 + k2 y^2) /
   * 2, unit mass. */
  class Oscillator : public MechanicalSystem
  {
  public:
    Oscillator()
      : inverse_masses(2)
    {
      inverse_masses = 1.;
    }
    std::string
    name() const override
    {
      return "oscillator";
    }
    unsigned int
    spatial_dimension() const override
    {
      return 2;
    }
    unsigned int
    n_dofs() const override
    {
      return 2;
    }
    const Vector &
    inverse_mass() const override
    {
      return inverse_masses;
    }
    double
    energy(const Vector &q) const override
    {
      return 0.5 * (k[0] * q[0] * q[0] + k[1] * q[1] * q[1]);
    }
    void
    gradient(const Vector &q, Vector &g) const override
    {
      g.reinit(2);
      g[0] = k[0] * q[0];
      g[1] = k[1] * q[1];
    }
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override
    {
      double c0 = 0., c1 = 0., c2 = 0.;
      for (unsigned int i = 0; i < 2; ++i)
        {
          c0 += 0.5 * k[i] * q[i] * q[i];
          c1 += k[i] * q[i] * v[i];
          c2 += 0.5 * k[i] * v[i] * v[i];
        }
      return std::make_unique<estep::testing::PolynomialFlight>(
        std::vector<double>{c0, c1, c2});
    }
    const double k[2] = {1., 2.3};

  private:
    Vector inverse_masses;
  };

  /** The oscillator under a constraint that is touched and approached at
   * every instant, whatever the reflections: contacts that hold each other. */
  class HeldOscillator : public Oscillator
  {
  public:
    std::optional<ConstraintEvent>
    first_constraint_event(const Vector &,
                           const Vector &v,
                           const double) const override
    {
      return ConstraintEvent{0., v};
    }
    bool
    has_constraints() const override
    {
      return true;
    }
  };

  TEST(EnergyStepping, StallsOnContactsThatReflectionsCannotPart)
  {
    const HeldOscillator held;
    Vector               q0(2), v0(2);
    q0[0] = 1.;
    v0[1] = 1.;
    EnergyStepping stepping(held, 1e-3);
    stepping.initialize(0., q0, v0);
    try
      {
        stepping.step(1.);
        FAIL() << "a step through contacts that hold each other";
      }
    catch (const StalledRun &stalled)
      {
        EXPECT_NE(std::string(stalled.what()).find("after 1000 reflections"),
                  std::string::npos)
          << stalled.what();
      }
    EXPECT_EQ(stepping.n_steps(), 0u);
  }

  TEST(EnergyStepping, ConvergesToTheExactMotionOfAHarmonicOscillator)
  {
    const Oscillator oscillator;
    Vector           q0(2), v0(2);
    q0[0]              = 1.;
    q0[1]              = 0.5;
    v0[0]              = 0.3;
    v0[1]              = -0.7;
    const double E     = oscillator.energy(q0) + 0.5 * (v0 * v0);
    const double T_end = 10.;
    const auto   exact = [&](const double t, const unsigned int i) {
      const double w = std::sqrt(oscillator.k[i]);
      return q0[i] * std::cos(w * t) + v0[i] / w * std::sin(w * t);
    };

    // The time spent on the last terrace before a turning point is O(h^1/2), so
    // the position error converges like h^1/2 (the reference text's rate).
    double              previous_error = 1e300;
    std::vector<double> errors;
    for (const double relative_step : {1e-2, 1e-3, 1e-4, 1e-5})
      {
        EnergyStepping stepping(oscillator, relative_step * E);
        stepping.initialize(0., q0, v0);
        double error = 0.;
        for (unsigned int k = 1; k <= 100; ++k)
          {
            const double t = k * T_end / 100.;
            while (stepping.time() < t)
              stepping.step(T_end);
            const Snapshot s = stepping.dense_output(t);
            error =
              std::max(error,
                       std::hypot(s.q[0] - exact(t, 0), s.q[1] - exact(t, 1)));
          }
        std::cout << "h = " << relative_step << " E: " << stepping.n_steps()
                  << " steps, maximum position error " << error << '\n';
        EXPECT_LT(error, 0.8 * previous_error);
        previous_error = error;
        errors.push_back(error);
      }
    const double rate = std::log10(errors[1] / errors[3]) / 2.;
    std::cout << "rate over h = 1e-3 ... 1e-5 E: " << rate << '\n';
    EXPECT_GT(rate, 0.3);
    EXPECT_LT(rate, 0.7);
    EXPECT_LT(errors[3], 0.02);
  }

  /** Checks after every step that V stayed on the flight's terrace at many
   * points. */
  class TerraceAudit : public RunObserver
  {
  public:
    TerraceAudit(const EnergyStepping &stepping)
      : stepping(stepping)
    {}

    void
    after_step(const TimeIntegrator &) override
    {
      const double a = stepping.previous_time(), b = stepping.time();
      for (unsigned int k = 1; k < 32; ++k)
        {
          const Snapshot s   = stepping.dense_output(a + (b - a) * k / 32.);
          const double   h   = stepping.energy_step();
          const double   L   = s.terraced_potential_energy;
          const double   tol = 1e-9 * h;
          worst              = std::max({worst,
                                         (L - tol) - s.potential_energy,
                                         s.potential_energy - (L + h + tol)});
        }
    }

    const EnergyStepping &stepping;
    double                worst = -1e300;
  };

  TEST(EnergyStepping, NeverStepsOverALevelOfTheArgonCluster)
  {
    const Problem argon = estep::testing::argon_cluster();
    for (const double h : {1e-1, 1e-2, 1e-3})
      {
        EnergyStepping stepping(*argon.system, h);
        stepping.initialize(0., argon.q0, argon.v0);
        TerraceAudit     audit(stepping);
        TimeLoopSettings settings;
        settings.end_time        = 2.;
        settings.output_interval = 0.;
        const TimeLoopResult result =
          run_time_loop(stepping, settings, {&audit});
        EXPECT_EQ(result.status, RunStatus::completed);
        EXPECT_LE(audit.worst, 0.)
          << "V left its terrace inside a flight, h = " << h;
      }
  }

  TEST(EnergyStepping, RejectsAnInvalidEnergyStep)
  {
    const Problem argon = estep::testing::argon_cluster();
    EXPECT_THROW(EnergyStepping(*argon.system, 0.), std::invalid_argument);
    EXPECT_THROW(EnergyStepping(*argon.system, -1.), std::invalid_argument);
  }

  TEST(TimeLoop, OutputsAtTheRequestedTimesExactly)
  {
    const Problem  argon = estep::testing::argon_cluster();
    EnergyStepping stepping(*argon.system, 1e-2);
    stepping.initialize(0., argon.q0, argon.v0);
    struct Recorder : RunObserver
    {
      void
      observe(const Snapshot &s) override
      {
        times.push_back(s.t);
      }
      std::vector<double> times;
    } recorder;
    TimeLoopSettings settings;
    settings.end_time        = 1.;
    settings.output_interval = 0.3;
    run_time_loop(stepping, settings, {&recorder});
    ASSERT_EQ(recorder.times.size(), 5u);
    EXPECT_EQ(recorder.times[0], 0.);
    EXPECT_NEAR(recorder.times[1], 0.3, 1e-15);
    EXPECT_NEAR(recorder.times[3], 0.9, 1e-15);
    EXPECT_EQ(recorder.times[4], 1.);
  }

  TEST(TimeLoop, AnObserverThatThrowsFailsTheRun)
  {
    // A plugin's observer (or integrator) that throws ends the run with
    // status failed and a message with the time, whatever it throws.
    const Problem argon = estep::testing::argon_cluster();
    struct Thrower : RunObserver
    {
      explicit Thrower(const bool standard)
        : standard(standard)
      {}
      void
      observe(const Snapshot &s) override
      {
        if (s.t < 0.5)
          return;
        if (standard)
          throw std::logic_error("deliberate");
        throw 42;
      }
      bool standard;
    };
    for (const bool standard : {true, false})
      {
        EnergyStepping stepping(*argon.system, 1e-2);
        stepping.initialize(0., argon.q0, argon.v0);
        Thrower          thrower(standard);
        TimeLoopSettings settings;
        settings.end_time        = 1.;
        settings.output_interval = 0.3;
        const TimeLoopResult result =
          run_time_loop(stepping, settings, {&thrower});
        EXPECT_EQ(result.status, RunStatus::failed);
        const std::string what =
          standard ? ": deliberate" : ": an exception of an unknown type";
        EXPECT_EQ(result.message.rfind("The run failed at t = 0.6", 0), 0u)
          << result.message;
        EXPECT_EQ(result.message.substr(result.message.size() - what.size()),
                  what);
        EXPECT_GE(result.final_time, 0.6);
      }
  }

  /** A drifting integrator (q += dt v) that breaks one rule of a time
   * integrator, as one of a user's own may. */
  class RuleBreaker : public estep::TimeIntegrator
  {
  public:
    enum class Rule
    {
      none,
      past_limit,
      no_count,
      stands_still
    };
    RuleBreaker(const estep::MechanicalSystem &system, const Rule broken)
      : TimeIntegrator(system)
      , broken(broken)
    {}
    std::string
    name() const override
    {
      return "rule breaker";
    }
    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override
    {
      t = t_previous = t0;
      q              = q0;
      v              = v0;
    }
    void
    step(const double t_limit) override
    {
      const double dt = broken == Rule::stands_still && t >= 0.6 ? 0. : 0.3;
      t_previous      = t;
      t = broken == Rule::past_limit ? t + dt : std::min(t + dt, t_limit);
      q.add(t - t_previous, v);
      if (broken != Rule::no_count)
        count_step();
      if (dt == 0.)
        ++n_waits;
    }
    estep::Snapshot
    dense_output(const double time) const override
    {
      return hermite_dense_output(time, q, v);
    }
    std::vector<estep::Counter>
    counters() const override
    {
      return {{"steps", n_steps()}, {"waits", n_waits}, {"never", 0}};
    }

  private:
    const Rule    broken;
    std::uint64_t n_waits = 0;
  };

  TEST(TimeLoop, AnIntegratorThatBreaksItsRulesFailsTheRun)
  {
    const Problem    argon = estep::testing::argon_cluster();
    TimeLoopSettings settings;
    settings.end_time        = 1.;
    settings.output_interval = 0.5;
    const auto run           = [&](const RuleBreaker::Rule rule) {
      RuleBreaker integrator(*argon.system, rule);
      integrator.initialize(0., argon.q0, argon.v0);
      return run_time_loop(integrator, settings, {});
    };
    EXPECT_EQ(run(RuleBreaker::Rule::none).status, RunStatus::completed);
    const TimeLoopResult past = run(RuleBreaker::Rule::past_limit);
    EXPECT_EQ(past.status, RunStatus::failed);
    EXPECT_NE(past.message.find("rule breaker stepped from t = 0.9 to 1.2, "
                                "past the limit 1 it was given"),
              std::string::npos)
      << past.message;
    const TimeLoopResult uncounted = run(RuleBreaker::Rule::no_count);
    EXPECT_EQ(uncounted.status, RunStatus::failed);
    EXPECT_NE(uncounted.message.find("without counting the step"),
              std::string::npos)
      << uncounted.message;
    // Steps that leave the time where it is end the run as stalled, with
    // what the integrator did meanwhile (the counters that changed).
    const TimeLoopResult still = run(RuleBreaker::Rule::stands_still);
    EXPECT_EQ(still.status, RunStatus::stalled);
    EXPECT_EQ(still.message,
              "The run stalled at t = 0.6: 10000 steps in a row did not "
              "advance the time (rule breaker, the last 9999 of them: steps "
              "+9999 waits +9999).");
  }

  /** The oscillator at rest on a level (V = 0), with flights whose
   * enclosures prove nothing: the first search crawls, and a signal arrives
   * at its 3000th enclosure. */
  class CrawlingOscillator : public Oscillator
  {
  public:
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &, const Vector &) const override
    {
      return std::make_unique<estep::testing::UselessEnclosureFlight>(
        0., [](const std::uint64_t n) {
          if (n == 3000)
            request_interruption(15);
        });
    }
  };

  TEST(TimeLoop, ASignalDuringACrawlingSearchEndsTheRunWithACheckpoint)
  {
    const CrawlingOscillator crawling;
    Vector                   q0(2), v0(2);
    v0[0] = 1.;
    EnergyStepping stepping(crawling, 1.);
    stepping.initialize(0., q0, v0);
    unsigned int     checkpoints = 0;
    TimeLoopSettings settings;
    settings.end_time           = 1.;
    settings.write_checkpoint   = [&](const TimeLoopState &) { ++checkpoints; };
    const TimeLoopResult result = run_time_loop(stepping, settings, {});
    request_interruption(0);
    EXPECT_EQ(result.status, RunStatus::interrupted);
    EXPECT_EQ(result.signal, 15);
    EXPECT_EQ(result.message,
              "Interrupted by signal 15 at t = 0 (in the middle of a step, "
              "which was abandoned).");
    // The state is the one the abandoned step started from.
    EXPECT_EQ(stepping.n_steps(), 0u);
    EXPECT_EQ(stepping.time(), 0.);
    EXPECT_EQ(stepping.velocity()[0], 1.);
    EXPECT_EQ(checkpoints, 1u);
  }
} // namespace
