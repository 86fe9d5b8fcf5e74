// Energy-stepping through collisions of two small balls: penalty and exact
// impenetrability, conservation of the terraced energy and the momenta, no
// interpenetration, no tunnelling at high speed; the flight enclosures hold
// sampled values along the penalty collision.

#include <estep/composite/contact_system.h>
#include <estep/time_integration/energy_stepping.h>

#include <gtest/gtest.h>

#include "../terrace_audit.h"
#include "contact_test_bodies.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

using estep::ContactParameters;
using estep::Vector;

namespace
{
  struct RunFigures
  {
    unsigned long steps = 0, constraint_events = 0;
    double        energy_error = 0., linear_error = 0., angular_error = 0.;
    /** The largest excursion of V beyond its flight's levels, in units of h,
     * over 64 samples inside every flight. */
    double                 terrace_excursion      = -1.;
    unsigned int           max_intersecting_pairs = 0;
    unsigned long          n_enclosure_samples = 0, n_outside = 0;
    bool                   reached_end             = false;
    double                 min_distance_of_centres = 1e300;
    estep::RigidBodyMotion final_1, final_2;
  };

  double
  norm3(const double *x)
  {
    return std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }

  /** Ball 2 moves towards ball 1 (at rest) with @p speed, spinning with 0.5
   * speed about y; energy step h = fraction of the initial kinetic energy. */
  RunFigures
  collide(const ContactParameters &parameters,
          const double             speed,
          const double             lambda0,
          const double             mu0,
          const double             h_fraction,
          const double             t_end,
          const bool               check_intersections,
          const bool               sample_enclosures = false)
  {
    const double gap = 0.1;
    const auto   system =
      estep_test::two_balls(2. + gap, 0.6, parameters, lambda0, mu0, 1.);
    // A small random deformation puts V(q0) well inside a terrace (the
    // undeformed state has V = 0 to round-off, exactly on a level, where the
    // enclosures cannot separate V from the level).
    Vector q0 = estep_test::reference(*system);
    q0 += estep_test::random_vector(q0.size(), 1e-3, 11);
    // Slightly off-centre to make the contact generic and the angular momentum
    // about the origin non-trivial.
    const Vector v0 =
      estep_test::rigid_velocities(*system,
                                   q0,
                                   {{{0., 0., 0.}},
                                    {{-speed, 0.05 * speed, 0.}}},
                                   {{{0., 0., 0.}}, {{0., 0.5 * speed, 0.}}});
    const double T0 = estep::kinetic_energy(*system, v0);

    estep::EnergyStepping integrator(*system, h_fraction * T0);
    integrator.initialize(0., q0, v0);
    const double         E0 = integrator.terraced_energy();
    const estep::Momenta m0 = estep::compute_momenta(*system, q0, v0);
    RunFigures           r;
    const char          *limit_env = std::getenv("ESTEP_TEST_T_END");
    const double         t_stop    = limit_env ? std::atof(limit_env) : t_end;
    std::mt19937_64      rng(17);
    std::uniform_real_distribution<double> u(0., 1.);
    double                                 last_step = 0.;
    while (integrator.time() < t_stop)
      {
        if (sample_enclosures && r.steps % 4 == 0)
          {
            // Random subintervals of the next flight (up to twice the last
            // step): every sampled value and slope lies in the enclosure.
            const auto flight =
              system->free_flight(integrator.position(), integrator.velocity());
            const double span  = std::min(std::max(2. * last_step, 1e-6),
                                         0.999 * flight->admissible_limit());
            const double width = span * std::pow(10., -6. * u(rng));
            const double a     = (span - width) * u(rng);
            const auto   e     = flight->enclose(a, a + width);
            for (unsigned int j = 0; j <= 10; ++j)
              {
                const auto lv =
                  flight->value_and_derivative(a + width * j / 10.);
                ++r.n_enclosure_samples;
                if (!e.value.contains(lv.value) ||
                    !e.derivative.contains(lv.derivative))
                  ++r.n_outside;
              }
          }
        const double t_before = integrator.time();
        integrator.step(t_stop);
        last_step = integrator.time() - t_before;
        ++r.steps;
        r.terrace_excursion =
          std::max(r.terrace_excursion,
                   estep_test::terrace_excursion(integrator));
        const Vector &q = integrator.position();
        const Vector &v = integrator.velocity();
        r.energy_error =
          std::max(r.energy_error,
                   std::abs(integrator.terraced_energy() - E0) / E0);
        const estep::Momenta m = estep::compute_momenta(*system, q, v);
        double               dl[3], da[3];
        for (unsigned int d = 0; d < 3; ++d)
          {
            dl[d] = m.linear[d] - m0.linear[d];
            da[d] = m.angular[d] - m0.angular[d];
          }
        r.linear_error = std::max(r.linear_error, norm3(dl) / norm3(m0.linear));
        r.angular_error =
          std::max(r.angular_error, norm3(da) / norm3(m0.angular));
        const auto b1 = system->body_motion(q, v, 0);
        const auto b2 = system->body_motion(q, v, 1);
        double     c[3];
        for (unsigned int d = 0; d < 3; ++d)
          c[d] = b2.centre[d] - b1.centre[d];
        r.min_distance_of_centres =
          std::min(r.min_distance_of_centres, norm3(c));
        if (check_intersections)
          r.max_intersecting_pairs =
            std::max(r.max_intersecting_pairs, system->n_intersecting_pairs(q));
        if (std::getenv("ESTEP_TEST_VERBOSE") && r.steps % 1000 == 0)
          std::cout << "step " << r.steps << " t = " << integrator.time()
                    << std::endl;
        // A search that crawls shows as a run that never ends: these runs
        // take a few thousand steps. A run that lost its energy is over too.
        if (r.steps >= 20000 || r.energy_error > 1e-6)
          break;
      }
    r.reached_end = integrator.time() >= t_stop;
    for (const auto &c : integrator.counters())
      if (c.first == "constraint events")
        r.constraint_events = c.second;
    r.final_1 =
      system->body_motion(integrator.position(), integrator.velocity(), 0);
    r.final_2 =
      system->body_motion(integrator.position(), integrator.velocity(), 1);
    std::cout << ContactParameters::mode_name(parameters.mode) << ", speed "
              << speed << ": " << r.steps << " steps, " << r.constraint_events
              << " constraint events, t = " << integrator.time()
              << "; max relative errors: E_h " << r.energy_error << ", P "
              << r.linear_error << ", L " << r.angular_error
              << "; largest excursion beyond a level " << r.terrace_excursion
              << " h; closest centres " << r.min_distance_of_centres
              << "; V1_x " << r.final_1.velocity[0] << ", V2_x "
              << r.final_2.velocity[0] << std::endl;
    if (sample_enclosures)
      std::cout << r.n_enclosure_samples << " sampled values and slopes, "
                << r.n_outside << " outside their enclosures" << std::endl;
    return r;
  }
} // namespace

// Through the whole collision (contact from t = 0.1 to about 1.7).
TEST(ContactCollision, PenaltyConservesThroughCollision)
{
  ContactParameters p;
  p.mode              = ContactParameters::Mode::penalty;
  p.penalty_parameter = 1e-3;
  const RunFigures r  = collide(p, 1., 10., 5., 1e-3, 2.0, false, true);
  EXPECT_TRUE(r.reached_end);
  EXPECT_LT(r.energy_error, 1e-10);
  EXPECT_LT(r.linear_error, 1e-10);
  EXPECT_LT(r.angular_error, 1e-10);
  EXPECT_EQ(r.n_outside, 0u);
  EXPECT_LT(r.terrace_excursion, 1e-8);
  // They touched (closer than 2 + gap) and ball 1 took over most of the
  // momentum of ball 2 (nearly elastic, like the impenetrability run).
  EXPECT_LT(r.min_distance_of_centres, 2.);
  EXPECT_LT(r.final_1.velocity[0], -0.8);
  EXPECT_GT(r.final_2.velocity[0], -0.2);
}

TEST(ContactCollision, ImpenetrabilityConservesAndNeverIntersects)
{
  ContactParameters p;
  p.mode             = ContactParameters::Mode::impenetrability;
  const RunFigures r = collide(p, 1., 10., 5., 1e-3, 2.0, true);
  EXPECT_TRUE(r.reached_end);
  EXPECT_LT(r.terrace_excursion, 1e-8);
  EXPECT_EQ(r.max_intersecting_pairs, 0u);
  EXPECT_GT(r.constraint_events, 0u);
  EXPECT_LT(r.energy_error, 1e-10);
  EXPECT_LT(r.linear_error, 1e-10);
  EXPECT_LT(r.angular_error, 1e-10);
  EXPECT_LT(r.final_1.velocity[0], -0.1);
}

TEST(ContactCollision, NoTunnellingAtHighSpeed)
{
  ContactParameters p;
  p.mode = ContactParameters::Mode::impenetrability;
  // Relative speed 100 on a stiff material; without contact the balls would
  // pass through each other by t = 0.041.
  const RunFigures r = collide(p, 100., 1e5, 5e4, 1e-3, 0.03, true);
  EXPECT_TRUE(r.reached_end);
  EXPECT_EQ(r.max_intersecting_pairs, 0u);
  EXPECT_GT(r.constraint_events, 0u);
  EXPECT_GT(r.min_distance_of_centres, 1.5);
  EXPECT_LT(r.energy_error, 1e-10);
  EXPECT_LT(r.linear_error, 1e-10);
  EXPECT_LT(r.angular_error, 1e-10);
}

// Forward into the collision, velocities flipped, back for as long. The
// penalty mode comes back to the start to round-off amplified by the
// crossings; the impenetrable mode to the margin of its conservative first
// contact (it reflects a little before the exact contact, forwards and
// backwards alike, so the two paths differ by that margin: measured 3e-8 in
// the positions, 5e-7 in the velocities).
TEST(ContactCollision, IsTimeReversibleThroughTheContact)
{
  for (const auto mode : {ContactParameters::Mode::penalty,
                          ContactParameters::Mode::impenetrability})
    {
      ContactParameters p;
      p.mode              = mode;
      p.penalty_parameter = 1e-3;
      const auto system   = estep_test::two_balls(2.05, 0.6, p, 10., 5., 1.);
      Vector     q0       = estep_test::reference(*system);
      q0 += estep_test::random_vector(q0.size(), 1e-3, 11);
      const Vector v0 =
        estep_test::rigid_velocities(*system,
                                     q0,
                                     {{{0., 0., 0.}}, {{-1., 0.05, 0.}}},
                                     {{{0., 0., 0.}}, {{0., 0.5, 0.}}});
      const double T = 0.3, h = 1e-3 * estep::kinetic_energy(*system, v0);
      estep::EnergyStepping forward(*system, h);
      forward.initialize(0., q0, v0);
      while (forward.time() < T)
        forward.step(T);
      Vector v_back = forward.velocity();
      v_back *= -1.;
      estep::EnergyStepping backward(*system, h);
      backward.initialize(T, forward.position(), v_back);
      while (backward.time() < 2. * T)
        backward.step(2. * T);
      Vector dq = backward.position(), dv = backward.velocity();
      dq -= q0;
      dv += v0;
      unsigned long events = 0;
      for (const auto &c : forward.counters())
        if (c.first == "constraint events" || c.first == "climbs")
          events += c.second;
      const auto motion =
        system->body_motion(forward.position(), forward.velocity(), 0);
      std::cout << ContactParameters::mode_name(mode) << ": "
                << forward.n_steps() << " steps forward, " << backward.n_steps()
                << " back, ball 1 moving at " << motion.velocity[0]
                << "; position error " << dq.l2_norm() / q0.l2_norm()
                << ", velocity error " << dv.l2_norm() / v0.l2_norm()
                << " (relative)" << std::endl;
      // Ball 1, at rest at first, was set moving by the contact.
      EXPECT_LT(motion.velocity[0], -0.02);
      EXPECT_GT(events, 0u);
      const double tolerance =
        mode == ContactParameters::Mode::penalty ? 1e-9 : 1e-5;
      EXPECT_LT(dq.l2_norm() / q0.l2_norm(), tolerance);
      EXPECT_LT(dv.l2_norm() / v0.l2_norm(), tolerance);
    }
}
