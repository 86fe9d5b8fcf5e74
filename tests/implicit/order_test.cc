// The implicit (SUNDIALS) integrators against the exact motion of coupled
// harmonic oscillators: observed orders of convergence and energy errors
// bounded from both sides.
#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/ida_bdf.h>

#include <gtest/gtest.h>

#include "../fitted_slope.h"
#include "../time_integration/harmonic_oscillator.h"
#include "implicit_test_support.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <vector>

namespace
{
  using estep::testing::HarmonicOscillator;

  const HarmonicOscillator &
  oscillator()
  {
    static const HarmonicOscillator system;
    return system;
  }

  /** The figures of one run to the end time. */
  struct OscillatorRun
  {
    /** Steps taken. */
    double steps;
    /** Largest error of a position or velocity component at the step ends. */
    double error;
    /** Extremes of (E(t) - E(0)) / E(0) at the step ends. */
    double                      energy_min, energy_max;
    std::vector<estep::Counter> counters;
  };

  /**
   * Run @p integrator from the oscillator's initial state, multiplied by
   * @p scale, to @p t_end; errors are reported relative to @p scale. A run
   * that needs more than @p max_steps steps (a collapsing step size) fails.
   */
  OscillatorRun
  run(estep::TimeIntegrator &integrator,
      const double           t_end,
      const double           max_steps = 3e5,
      const double           scale     = 1.)
  {
    estep::Vector q0, v0, q_exact, v_exact;
    HarmonicOscillator::initial_state(q0, v0);
    q0 *= scale;
    v0 *= scale;
    const double E0 = oscillator().total_energy(q0, v0);
    integrator.initialize(0., q0, v0);
    OscillatorRun result{0., 0., 0., 0., {}};
    while (integrator.time() < t_end)
      {
        integrator.step(t_end);
        const estep::Vector &q = integrator.position();
        const estep::Vector &v = integrator.velocity();
        oscillator().exact_state(integrator.time(), q0, v0, q_exact, v_exact);
        for (unsigned int i = 0; i < 2; ++i)
          result.error = std::max({result.error,
                                   std::abs(q[i] - q_exact[i]),
                                   std::abs(v[i] - v_exact[i])});
        const double dE   = (oscillator().total_energy(q, v) - E0) / E0;
        result.energy_min = std::min(result.energy_min, dE);
        result.energy_max = std::max(result.energy_max, dE);
        if (integrator.n_steps() > max_steps)
          {
            ADD_FAILURE() << integrator.name() << ": more than " << max_steps
                          << " steps, stopped at t = " << integrator.time();
            break;
          }
        // Newton never fails on this linear problem with an exact Newton
        // matrix: stop a run that keeps failing (a wrong matrix) early.
        if (integrator.n_steps() % 100 == 0 &&
            estep_test::counter(integrator.counters(),
                                "newton convergence failures") > 20)
          {
            ADD_FAILURE() << integrator.name()
                          << ": more than 20 Newton convergence failures, "
                             "stopped at t = "
                          << integrator.time();
            break;
          }
      }
    EXPECT_EQ(integrator.time(), t_end);
    result.error /= scale;
    result.steps    = integrator.n_steps();
    result.counters = integrator.counters();
    return result;
  }

  /** Newton iterations per step of a run. */
  double
  newton_per_step(const OscillatorRun &r)
  {
    return estep_test::counter(r.counters, "newton iterations") / r.steps;
  }

  void
  print(const std::string &label, const OscillatorRun &r)
  {
    std::cout << label << ": " << r.steps << " steps, error " << r.error
              << ", energy error in [" << r.energy_min << ", " << r.energy_max
              << "], Newton iterations per step " << newton_per_step(r)
              << ", Jacobian setups "
              << estep_test::counter(r.counters, "jacobian setups")
              << ", Newton convergence failures "
              << estep_test::counter(r.counters, "newton convergence failures")
              << ", error test failures "
              << estep_test::counter(r.counters, "error test failures") << '\n';
  }

  /** An IdaBdf that records the highest order its steps used. */
  class ObservedIdaBdf : public estep::IdaBdf
  {
  public:
    using estep::IdaBdf::IdaBdf;

    void
    step(const double t_limit) override
    {
      estep::IdaBdf::step(t_limit);
      *highest_order = std::max(*highest_order, last_order());
    }

    int *highest_order = nullptr;
  };

  /** What an adaptive method must show on the oscillator. */
  struct Expectation
  {
    /** Window of the observed order. */
    double order_min, order_max;
    /**
     * Window of the lowest relative energy error min_t (E(t) - E(0)) / E(0)
     * at the tolerance 1e-6, and the most the energy may grow at any
     * tolerance.
     */
    double energy_min_low, energy_min_high, energy_growth;
    /** Most Newton iterations per step, and Newton-matrix setups per step. */
    double newton_per_step, setups_per_step;
  };

  /**
   * An adaptive method at the tolerances 1e-4 ... 1e-8 (relative = absolute):
   * the order is the slope of log(error) against -log(steps) (error ~ N^-p
   * when the step size follows the local error control). The energy error
   * is bounded both ways at every tolerance (by three times the state error,
   * as E is a smooth function of the state, and by @p expected's growth
   * limit) and lies in a stated window at 1e-6. Newton never fails to
   * converge on this linear problem with an exact Newton matrix.
   */
  void
  check_adaptive(const std::string                     &label,
                 const std::function<std::unique_ptr<estep::TimeIntegrator>(
                   const estep::ImplicitParameters &)> &create,
                 const Expectation                     &expected)
  {
    std::vector<double> steps, errors;
    for (const double tolerance : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8})
      {
        estep::ImplicitParameters parameters;
        parameters.relative_tolerance  = tolerance;
        parameters.absolute_tolerance  = tolerance;
        const auto          integrator = create(parameters);
        const OscillatorRun r          = run(*integrator, 10.);
        print(label + ", tolerance " + std::to_string(tolerance), r);
        steps.push_back(r.steps);
        errors.push_back(r.error);
        EXPECT_GE(r.energy_min, -3. * r.error) << label << " at " << tolerance;
        EXPECT_LE(r.energy_max, 3. * r.error) << label << " at " << tolerance;
        EXPECT_LE(r.energy_max, expected.energy_growth)
          << label << " at " << tolerance;
        if (tolerance == 1e-6)
          {
            EXPECT_GE(r.energy_min, expected.energy_min_low) << label;
            EXPECT_LE(r.energy_min, expected.energy_min_high) << label;
          }
        EXPECT_EQ(estep_test::counter(r.counters,
                                      "newton convergence failures"),
                  0u)
          << label << " at " << tolerance;
        EXPECT_LE(newton_per_step(r), expected.newton_per_step)
          << label << " at " << tolerance;
        EXPECT_LE(estep_test::counter(r.counters, "jacobian setups"),
                  expected.setups_per_step * r.steps + 10.)
          << label << " at " << tolerance;
        if (testing::Test::HasFailure())
          return; // fail fast: the tighter tolerances would only take longer
      }
    const double order = -estep_test::fitted_slope(steps, errors);
    std::cout << label << ": observed order " << order << '\n';
    EXPECT_GE(order, expected.order_min) << label;
    EXPECT_LE(order, expected.order_max) << label;
  }

  /**
   * The implicit midpoint rule at a fixed step: second order; the energy of
   * a linear system (a quadratic invariant) is conserved to round-off both
   * ways. With an exact Newton matrix each step's linear problem is solved by
   * the first Newton iteration and confirmed by the second, without a
   * failure, and the matrix is set up every jacobian_update_interval steps
   * only: a wrong Newton matrix shows in these counts even where the
   * iteration still converges.
   */
  TEST(ImplicitOrder, ArkodeMidpointIsSecondOrderAndConservesEnergy)
  {
    std::vector<double> steps, errors;
    for (const double dt : {0.1, 0.05, 0.025, 0.0125})
      {
        estep::ImplicitParameters parameters;
        parameters.newton_tolerance = 1e-10;
        estep::ArkodeRungeKutta integrator(
          oscillator(),
          parameters,
          estep::ArkodeRungeKutta::Method::midpoint,
          dt);
        const OscillatorRun r = run(integrator, 10.);
        print("midpoint, dt " + std::to_string(dt), r);
        steps.push_back(dt);
        errors.push_back(r.error);
        EXPECT_EQ(r.steps, std::round(10. / dt));
        EXPECT_LT(r.energy_max, 1e-12);
        EXPECT_GT(r.energy_min, -1e-12);
        EXPECT_EQ(newton_per_step(r), 2.);
        EXPECT_LE(estep_test::counter(r.counters, "jacobian setups"),
                  r.steps / parameters.jacobian_update_interval + 1);
        EXPECT_EQ(estep_test::counter(r.counters,
                                      "newton convergence failures"),
                  0u);
      }
    const double order = estep_test::fitted_slope(steps, errors);
    std::cout << "midpoint: observed order " << order << '\n';
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.2);
    EXPECT_LT(errors.back(), 2e-3);
  }

  /**
   * ARKode's adaptive DIRK methods of orders 2, 3 (the default) and 4: the
   * observed order, dissipation (the energy never grows, and decays by a
   * stated amount at the tolerance 1e-6), and the Newton matrix set up about
   * every jacobian_update_interval steps (a wrong matrix needs more setups).
   */
  TEST(ImplicitOrder, ArkodeDirkOrders)
  {
    const std::map<unsigned int, Expectation> expectations = {
      {2, {1.8, 2.3, -3e-7, -1e-8, 1e-10, 4., 0.3}},
      {3, {2.7, 3.4, -3e-4, -1e-5, 1e-10, 7., 0.3}},
      {4, {3.6, 4.6, -2e-8, -5e-10, 1e-10, 9.5, 0.3}}};
    for (const auto &[p, expected] : expectations)
      check_adaptive(
        "dirk " + std::to_string(p),
        [p = p](const estep::ImplicitParameters &parameters_in) {
          estep::ImplicitParameters parameters = parameters_in;
          parameters.arkode_order              = p;
          auto integrator = std::make_unique<estep::ArkodeRungeKutta>(
            oscillator(),
            parameters,
            estep::ArkodeRungeKutta::Method::dirk,
            1e-3);
          return std::unique_ptr<estep::TimeIntegrator>(std::move(integrator));
        },
        expected);
  }

  /**
   * IDA's BDF with the maximum orders 1, 2 and 5: the observed order, the
   * order actually used, and the energy: BDF1 and BDF2 dissipate (by a stated
   * amount at the tolerance 1e-6, backward Euler strongly), BDF5 keeps it
   * close. The Hessian of this system is constant: at most 10 Newton-matrix
   * setups per run.
   */
  TEST(ImplicitOrder, IdaBdfOrders)
  {
    const std::map<unsigned int, Expectation> expectations = {
      {1, {0.85, 1.15, -0.05, -0.01, 1e-10, 3., 0.}},
      {2, {1.75, 2.45, -1e-4, -1e-5, 1e-10, 3., 0.}},
      {5, {3.5, 6., -1e-3, 0., 1e-3, 3., 0.}}};
    for (const auto &[p, expected] : expectations)
      {
        int highest_order = 0;
        check_adaptive(
          "bdf " + std::to_string(p),
          [p = p,
           &highest_order](const estep::ImplicitParameters &parameters_in) {
            estep::ImplicitParameters parameters = parameters_in;
            parameters.maximum_bdf_order         = p;
            auto integrator =
              std::make_unique<ObservedIdaBdf>(oscillator(), parameters, 1e-3);
            integrator->highest_order = &highest_order;
            return std::unique_ptr<estep::TimeIntegrator>(
              std::move(integrator));
          },
          expected);
        EXPECT_EQ(highest_order, static_cast<int>(p));
      }
  }

  /**
   * The tolerances mean what they say: a motion a thousand times larger,
   * with the absolute tolerance a thousand times larger and the same
   * relative tolerance, takes the same steps and has the same relative error
   * (the problem is linear: the runs differ by the scale only). A method that
   * mixed up the two tolerances would take far fewer steps for the large
   * motion.
   */
  TEST(ImplicitOrder, TolerancesScaleWithTheMotion)
  {
    for (const std::string method : {"ida", "dirk"})
      {
        OscillatorRun runs[2];
        for (unsigned int k = 0; k < 2; ++k)
          {
            const double              scale = (k == 0 ? 1. : 1e3);
            estep::ImplicitParameters parameters;
            parameters.relative_tolerance = 1e-6;
            parameters.absolute_tolerance = 1e-7 * scale;
            std::unique_ptr<estep::TimeIntegrator> integrator;
            if (method == "ida")
              integrator =
                std::make_unique<estep::IdaBdf>(oscillator(), parameters, 1e-3);
            else
              integrator = std::make_unique<estep::ArkodeRungeKutta>(
                oscillator(),
                parameters,
                estep::ArkodeRungeKutta::Method::dirk,
                1e-3);
            runs[k] = run(*integrator, 10., 3e5, scale);
            print(method + ", scale " + std::to_string(scale), runs[k]);
          }
        EXPECT_NEAR(runs[1].steps, runs[0].steps, 0.05 * runs[0].steps)
          << method;
        EXPECT_NEAR(runs[1].error, runs[0].error, 0.2 * runs[0].error)
          << method;
      }
  }
} // namespace
