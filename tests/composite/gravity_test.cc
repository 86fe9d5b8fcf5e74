// Gravity as a decorator: the compensated dot product, the weights and the
// gradient (against central differences), the free flight against energy()
// and its enclosures against samples (a deformed moving cube, two overlapping
// balls in penalty contact, and a flight whose elastic slope cancels the
// weight's), and the free fall of an undeformed elastic cube: energy-stepping
// conserves its terraced energy, every descent gives the analytic speed, the
// time to a given depth converges to the parabola's at first order in h, and
// explicit Newmark reproduces the parabola to round-off.

#include <deal.II/grid/tria.h>

#include <estep/composite/contact_parameters.h>
#include <estep/composite/gravity.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/neo_hookean.h>
#include <estep/systems/rigid_body_motion.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/explicit_newmark.h>

#include <gtest/gtest.h>

#include "../fitted_slope.h"
#include "../terrace_audit.h"
#include "contact_test_bodies.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>

using estep::Gravity;
using estep::Vector;

namespace
{
  constexpr double standard_gravity = 9.81;

  /** The spinning-cube body of n^3 hexahedra of 24 tets (the unit cube,
   * lambda0 = 0.01, mu0 = 0.0066, rho = 0.1; as tests/fem/test_bodies.h,
   * whose random_vector() clashes with contact_test_bodies.h's). */
  std::shared_ptr<const estep::ElasticBody>
  cube_body(const unsigned int n)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n);
    return std::make_shared<const estep::ElasticBody>(
      tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
  }

  /** Total mass of the points of @p system (3D), from its inverse mass. */
  double
  total_mass(const estep::MechanicalSystem &system)
  {
    double mass = 0.;
    for (const double m : system.inverse_mass())
      mass += 1. / m;
    return mass / system.spatial_dimension();
  }

  /** The rigid part of the motion of all points of a 3D system. */
  estep::RigidBodyMotion
  motion(const estep::MechanicalSystem &system,
         const Vector                  &q,
         const Vector                  &v)
  {
    return estep::rigid_body_motion(
      system.inverse_mass(), q, v, 0, q.size() / 3);
  }

  /**
   * Check the enclosures of @p flight over random intervals of [0, @p limit]
   * against 21 samples each: values and slopes inside, the sample what
   * value_and_derivative() computes, the curvature the base flight's.
   * Returns the number of samples checked.
   */
  unsigned int
  check_enclosures(const estep::FreeFlight &flight,
                   const estep::FreeFlight &base_flight,
                   const double             limit,
                   const unsigned int       n_intervals,
                   const unsigned int       seed)
  {
    std::mt19937_64                        rng(seed);
    std::uniform_real_distribution<double> u(0., 1.);
    unsigned int                           n_samples = 0, n_sampled = 0;
    for (unsigned int k = 0; k < n_intervals; ++k)
      {
        const double width = limit * std::pow(10., -5. * u(rng));
        const double a     = (limit - width) * u(rng);
        const double b     = a + width;
        const auto   e     = flight.enclose(a, b);
        if (e.sample_point >= a && e.sample_point <= b)
          {
            ++n_sampled;
            const auto at_sample = flight.value_and_derivative(e.sample_point);
            EXPECT_EQ(e.sample.value, at_sample.value);
            EXPECT_EQ(e.sample.derivative, at_sample.derivative);
          }
        // The curvature and the sample point are the base's. (Asked after
        // the sample: the flights of a ContactSystem share its contact
        // term's scratch, which changes the last bits of their sums.)
        const auto eb = base_flight.enclose(a, b);
        EXPECT_EQ(e.curvature.lower, eb.curvature.lower);
        EXPECT_EQ(e.curvature.upper, eb.curvature.upper);
        EXPECT_TRUE(
          e.sample_point == eb.sample_point ||
          (std::isnan(e.sample_point) && std::isnan(eb.sample_point)));
        for (unsigned int j = 0; j <= 20; ++j)
          {
            const double s  = (j == 20) ? b : a + (b - a) * j / 20.;
            const auto   lv = flight.value_and_derivative(s);
            ++n_samples;
            EXPECT_TRUE(e.value.contains(lv.value))
              << std::setprecision(17) << "s = " << s << " in [" << a << ", "
              << b << "]: value " << lv.value << " not in [" << e.value.lower
              << ", " << e.value.upper << "]";
            EXPECT_TRUE(e.derivative.contains(lv.derivative))
              << std::setprecision(17) << "s = " << s << " in [" << a << ", "
              << b << "]: slope " << lv.derivative << " not in ["
              << e.derivative.lower << ", " << e.derivative.upper << "]";
            EXPECT_TRUE(e.value.contains(flight.value(s)));
          }
      }
    EXPECT_GT(n_sampled, 0u);
    return n_samples;
  }

  /** A deformed n = 2 cube under an oblique gravity, built once. */
  const Gravity &
  deformed_cube_under_gravity()
  {
    static const Gravity system(cube_body(2), {{0.3, -1.2, -standard_gravity}});
    return system;
  }

  /** A deformed configuration of the cube of deformed_cube_under_gravity(),
   * lifted by 2 (large potential). */
  Vector
  deformed_configuration()
  {
    const auto &body = dynamic_cast<const estep::ElasticBody &>(
      deformed_cube_under_gravity().base());
    Vector q = body.reference_configuration();
    q += estep_test::random_vector(q.size(), 0.02, 11);
    for (unsigned int i = 2; i < q.size(); i += 3)
      q[i] += 2.;
    return q;
  }

  /** A moving, deforming velocity field of that cube: a translation, a spin
   * and a random part. */
  Vector
  moving_velocity(const Vector &q, const unsigned int seed)
  {
    const auto &body = dynamic_cast<const estep::ElasticBody &>(
      deformed_cube_under_gravity().base());
    Vector v = body.rigid_velocity(q,
                                   {{0.4, 0.1, -0.7}},
                                   {{0.3, -0.5, 1.}},
                                   {{.5, .5, 2.5}});
    v += estep_test::random_vector(q.size(), 0.05, seed);
    return v;
  }

  /** The z coordinate of the centre of mass. */
  double
  centre_height(const estep::MechanicalSystem &system, const Vector &q)
  {
    return motion(system, q, q).centre[2];
  }
} // namespace



TEST(Gravity, CompensatedDotProduct)
{
  // An ill-conditioned sum: 1 + 10^16 x (1 - 1) hides the 1 from a plain
  // sum; the products are not exact either.
  Vector x(6), y(6);
  x[0] = 1e16;
  x[1] = 1.;
  x[2] = -1e16;
  x[3] = 0.1;
  x[4] = 3.;
  x[5] = -0.3;
  for (unsigned int i = 0; i < 6; ++i)
    y[i] = 1.;
  y[3]                 = 3.;
  y[4]                 = 0.1;
  y[5]                 = 1.;
  double     magnitude = 0.;
  const auto dot       = estep::compensated_dot(x, y, &magnitude);
  // Exactly: 1 + 0.1 * 3 + 3 * 0.1 - 0.3 with the doubles 0.1 and 0.3, within
  // one unit of round-off of the result.
  const long double exact = 1.L + 2.L * 3.L * static_cast<long double>(0.1) -
                            static_cast<long double>(0.3);
  EXPECT_NEAR(dot, static_cast<double>(exact), 2e-16);
  EXPECT_EQ(magnitude, 2e16 + 1. + 0.3 + 0.30000000000000004 + 0.3);
  Vector z(5);
  EXPECT_THROW(estep::compensated_dot(x, z), std::invalid_argument);
}

TEST(Gravity, CompensatedDotProductAcrossBlocks)
{
  // The large terms cancel across blocks of coordinates (1e16 in the first,
  // -1e16 in the third), so the blocks' sums must be joined without loss:
  // a plain sum of the blocks' results loses the ones in between.
  const unsigned int n = 3 * estep::block_size + 5;
  Vector             x(n), y(n);
  for (unsigned int i = 0; i < n; ++i)
    {
      x[i] = 1.;
      y[i] = 1.;
    }
  x[10]                    = 1e16;
  x[2 * estep::block_size] = -1e16;
  x[estep::block_size + 3] = 0.1;
  y[estep::block_size + 3] = 3.;
  const long double exact  = (n - 3) + 3.L * static_cast<long double>(0.1);
  // The same bits on any number of threads.
  estep::set_thread_count(1);
  double       magnitude = 0.;
  const double dot       = estep::compensated_dot(x, y, &magnitude);
  EXPECT_NEAR(dot, static_cast<double>(exact), 1e-12);
  EXPECT_NEAR(magnitude, 2e16, 1e-12 * 2e16); // summed plainly
  for (const unsigned int threads : {2u, 3u})
    {
      estep::set_thread_count(threads);
      EXPECT_EQ(estep::compensated_dot(x, y), dot) << threads << " threads";
    }
  estep::set_thread_count(1);
}

TEST(Gravity, WeightsAndRejectedArguments)
{
  const Gravity &system = deformed_cube_under_gravity();
  const auto    &body = dynamic_cast<const estep::ElasticBody &>(system.base());
  ASSERT_EQ(system.weights().size(), body.n_dofs());
  const auto &g = system.acceleration();
  for (unsigned int i = 0; i < body.n_vertices(); ++i)
    for (unsigned int c = 0; c < 3; ++c)
      EXPECT_NEAR(system.weights()[3 * i + c],
                  body.point_mass(i) * g[c],
                  1e-15 * body.point_mass(i) * std::abs(g[c]));
  // The potential: -sum_p m_p g . x_p, also as the last observable.
  const Vector q = deformed_configuration();
  double       V = 0., gross = 0.;
  for (unsigned int i = 0; i < body.n_vertices(); ++i)
    for (unsigned int c = 0; c < 3; ++c)
      {
        V -= body.point_mass(i) * g[c] * q[3 * i + c];
        gross += std::abs(body.point_mass(i) * g[c] * q[3 * i + c]);
      }
  EXPECT_NEAR(system.gravitational_potential(q), V, 1e-14 * gross);
  EXPECT_NEAR(system.energy(q),
              body.energy(q) + system.gravitational_potential(q),
              1e-15 * (std::abs(body.energy(q)) + gross));
  const auto names  = system.observable_names();
  const auto values = system.observables(q, q);
  ASSERT_EQ(names.size(), body.observable_names().size() + 1);
  ASSERT_EQ(values.size(), names.size());
  EXPECT_EQ(names.back(), "gravitational_potential");
  EXPECT_EQ(values.back(), system.gravitational_potential(q));
  // Forwarded: mass, layout, Hessian.
  EXPECT_EQ(&system.inverse_mass(), &body.inverse_mass());
  EXPECT_EQ(system.n_dofs(), body.n_dofs());
  EXPECT_EQ(system.has_hessian(), body.has_hessian());

  const auto cube = cube_body(1);
  EXPECT_THROW(Gravity(nullptr, {{0., 0., -1.}}), std::invalid_argument);
  EXPECT_THROW(Gravity(cube, {{0., std::nan(""), -1.}}), std::invalid_argument);
  EXPECT_NO_THROW(Gravity(cube, {{0., 0., 0.}}));
  EXPECT_THROW(Gravity(cube, {{0., 0., -1.}}, {cube->n_vertices()}),
               std::invalid_argument);
}

TEST(Gravity, WeightlessPointsHaveNoWeight)
{
  // The points of a rigid obstacle surface have a placeholder mass and must
  // add nothing to the potential, wherever the surface lies.
  const auto    cube = cube_body(1);
  const Gravity all(cube, {{0., 0., -9.81}});
  const Gravity without(cube, {{0., 0., -9.81}}, {0, 3});
  const Vector  q = cube->reference_configuration();
  for (unsigned int i = 0; i < q.size(); ++i)
    EXPECT_EQ(without.weights()[i],
              i / 3 == 0 || i / 3 == 3 ? 0. : all.weights()[i]);
  Vector raised = q;
  raised[2] += 10.;
  raised[3 * 3 + 2] += 10.;
  EXPECT_EQ(without.gravitational_potential(raised),
            without.gravitational_potential(q));
  EXPECT_GT(all.gravitational_potential(raised),
            all.gravitational_potential(q));
}

TEST(Gravity, GradientMatchesCentralDifferences)
{
  const Gravity &system = deformed_cube_under_gravity();
  const Vector   q      = deformed_configuration();
  Vector         g, g_base;
  system.gradient(q, g);
  system.base().gradient(q, g_base);
  // Exactly the base's minus the weights.
  for (unsigned int i = 0; i < q.size(); ++i)
    ASSERT_EQ(g[i], g_base[i] - system.weights()[i]);

  double worst = 0.;
  for (unsigned int k = 0; k < 10; ++k)
    {
      const Vector d  = estep_test::random_vector(q.size(), 1., 100 + k);
      const double h  = 1e-6;
      Vector       qp = q, qm = q;
      qp.add(h, d);
      qm.add(-h, d);
      const double fd    = (system.energy(qp) - system.energy(qm)) / (2. * h);
      const double exact = g * d;
      worst = std::max(worst, std::abs(fd - exact) / std::abs(exact));
    }
  std::cout << "gradient vs central differences: worst relative error " << worst
            << std::endl;
  EXPECT_LT(worst, 1e-7);

  // The gravitational part alone, component by component: exactly linear.
  double worst_component = 0.;
  for (unsigned int i = 0; i < q.size(); ++i)
    {
      Vector qp = q, qm = q;
      qp[i] += 1e-3;
      qm[i] -= 1e-3;
      const double fd = (system.gravitational_potential(qp) -
                         system.gravitational_potential(qm)) /
                        2e-3;
      worst_component = std::max(worst_component,
                                 std::abs(fd - (g[i] - g_base[i])) /
                                   system.weights().linfty_norm());
    }
  EXPECT_LT(worst_component, 1e-10);
}

TEST(Gravity, FlightMatchesEnergy)
{
  const Gravity &system = deformed_cube_under_gravity();
  const Vector   q      = deformed_configuration();
  const Vector   v      = moving_velocity(q, 3);
  const auto     flight = system.free_flight(q, v);
  const auto     base   = system.base().free_flight(q, v);
  EXPECT_GT(flight->value_tolerance(), base->value_tolerance());
  EXPECT_EQ(flight->admissible_limit(), base->admissible_limit());
  // The tolerance adds a few units of round-off of sum |w_i q_i|.
  double gross = 0.;
  for (unsigned int i = 0; i < q.size(); ++i)
    gross += std::abs(system.weights()[i] * q[i]);
  EXPECT_LE(flight->value_tolerance() - base->value_tolerance(),
            16. * std::numeric_limits<double>::epsilon() * gross);
  const double V0 = system.energy(q);
  EXPECT_NEAR(flight->value(0.), V0, flight->value_tolerance());
  for (const double s : {0., 1e-3, 0.01, 0.1, 0.2})
    {
      Vector x = q;
      x.add(s, v);
      const double V  = system.energy(x);
      const auto   lv = flight->value_and_derivative(s);
      EXPECT_NEAR(lv.value, V, 1e-13 * (gross + std::abs(V)));
      EXPECT_NEAR(lv.value, flight->value(s), 1e-15 * (gross + std::abs(V)));
      // The linear term: exactly c0 + c1 s on top of the base.
      const auto base_value = base->value_and_derivative(s);
      EXPECT_NEAR(lv.value - base_value.value,
                  system.gravitational_potential(x),
                  1e-14 * (gross + std::abs(V)));
      Vector g;
      system.gradient(x, g);
      EXPECT_NEAR(lv.derivative, g * v, 1e-12 * (std::abs(g * v) + 1.));
      EXPECT_NEAR(lv.derivative - base_value.derivative,
                  -estep::compensated_dot(system.weights(), v),
                  1e-15 * (std::abs(lv.derivative) +
                           std::abs(base_value.derivative)));
    }
}

TEST(Gravity, EnclosuresContainSampledValues)
{
  const Gravity &system    = deformed_cube_under_gravity();
  const Vector   q         = deformed_configuration();
  unsigned int   n_samples = 0;
  for (unsigned int f = 0; f < 4; ++f)
    {
      const Vector v      = moving_velocity(q, 20 + f);
      const auto   flight = system.free_flight(q, v);
      const auto   base   = system.base().free_flight(q, v);
      const double limit  = std::min(0.5, 0.999 * flight->admissible_limit());
      n_samples += check_enclosures(*flight, *base, limit, 60, 7 + f);
    }
  std::cout << n_samples << " samples of the deformed moving cube checked"
            << std::endl;
}

TEST(Gravity, EnclosuresOfAContactSystemContainSampledValues)
{
  estep::ContactParameters parameters;
  parameters.mode              = estep::ContactParameters::Mode::penalty;
  parameters.penalty_parameter = 1e-2;
  const std::shared_ptr<const estep::ContactSystem> balls =
    estep_test::two_balls(1.8, 0.6, parameters);
  const Gravity system(balls, {{-2., 0., -standard_gravity}});
  const Vector  q         = estep_test::reference(*balls);
  unsigned int  n_samples = 0;
  for (unsigned int f = 0; f < 3; ++f)
    {
      Vector v = estep_test::random_vector(q.size(), 0.3, 50 + f);
      for (unsigned int i = balls->point_offset(1); i < q.size() / 3; ++i)
        v[3 * i] -= 1.;
      const auto   flight = system.free_flight(q, v);
      const auto   base   = balls->free_flight(q, v);
      const double limit  = std::min(0.3, 0.999 * flight->admissible_limit());
      n_samples += check_enclosures(*flight, *base, limit, 25, 70 + f);
    }
  std::cout << n_samples << " samples of the balls in contact checked"
            << std::endl;
}

TEST(Gravity, EnclosureFollowsTheSlopeOfTheSum)
{
  // A gravity chosen so that its slope cancels the deformed cube's at the
  // centre of [a, b]: the value enclosure is as narrow as the slope of the
  // sum allows, not as wide as the sum of the two slopes.
  const auto   body = cube_body(2);
  const Vector q    = deformed_configuration();
  const Vector v    = moving_velocity(q, 5);
  const double a = 0.1, b = 0.1 + 1e-4, m = a + 0.5 * (b - a);
  const double slope =
    body->free_flight(q, v)->value_and_derivative(m).derivative;
  const auto p = motion(*body, q, v);
  // c1 = -g . P with the momentum P = M V: g = slope V / (M |V|^2).
  const double V2 = p.velocity[0] * p.velocity[0] +
                    p.velocity[1] * p.velocity[1] +
                    p.velocity[2] * p.velocity[2];
  std::array<double, 3> acceleration;
  for (unsigned int c = 0; c < 3; ++c)
    acceleration[c] = slope * p.velocity[c] / (p.mass * V2);
  const Gravity system(body, acceleration);
  const auto    flight = system.free_flight(q, v);
  const auto    base   = body->free_flight(q, v);
  const auto    e      = flight->enclose(a, b);
  const auto    eb     = base->enclose(a, b);
  const double  c1     = -estep::compensated_dot(system.weights(), v);
  ASSERT_NEAR(c1, -slope, 1e-12 * std::abs(slope));
  const double sum_of_slopes = (std::abs(slope) + std::abs(c1)) * (b - a);
  std::cout << "slopes " << slope << " and " << c1 << " on [" << a << ", " << b
            << "]: value enclosure width " << e.value.width() << " (base's "
            << eb.value.width() << ", sum of slopes x width " << sum_of_slopes
            << ")" << std::endl;
  EXPECT_GT(eb.value.width(), 0.5 * std::abs(slope) * (b - a));
  EXPECT_LT(e.value.width(), 0.01 * sum_of_slopes);
  EXPECT_LT(std::max(std::abs(e.derivative.lower),
                     std::abs(e.derivative.upper)),
            0.01 * std::abs(slope));
  check_enclosures(*flight, *base, 0.2, 40, 99);
}

namespace
{
  /** The free-fall set-up: the undeformed n = 2 cube (mass 0.1, the unit
   * cube) under g = (0, 0, -9.81), moving with (0.2, 0, -0.5). */
  struct FreeFall
  {
    std::shared_ptr<const estep::ElasticBody> body = cube_body(2);
    Gravity system{body, {{0., 0., -standard_gravity}}};
    Vector  q0 = body->reference_configuration();
    Vector  v0 = body->rigid_velocity(q0,
                                     {{0.2, 0., -0.5}},
                                     {{0., 0., 0.}},
                                     {{0.5, 0.5, 0.5}});
    double  M  = total_mass(system);

    /** The time the parabola takes to fall by @p depth. */
    double
    exact_time(const double depth) const
    {
      const double w = v0[2]; // vertical velocity (negative)
      return (w + std::sqrt(w * w + 2. * standard_gravity * depth)) /
             standard_gravity;
    }
  };

  /** The time energy-stepping with energy step @p h and terrace offset @p c
   * takes the free-falling cube's centre of mass to fall by @p depth. */
  double
  energy_stepping_fall_time(const FreeFall &fall,
                            const double    h,
                            const double    c,
                            const double    depth)
  {
    estep::EnergyStepping stepping(fall.system, h, c);
    stepping.initialize(0., fall.q0, fall.v0);
    const double target = centre_height(fall.system, fall.q0) - depth;
    double       z      = centre_height(fall.system, fall.q0);
    while (true)
      {
        const double t_before = stepping.time(), z_before = z;
        stepping.step(100.);
        z = centre_height(fall.system, stepping.position());
        if (z <= target)
          return t_before + (z_before - target) / (z_before - z) *
                              (stepping.time() - t_before);
        if (stepping.time() >= 100.)
          throw std::runtime_error("the cube did not fall");
      }
  }

  /** The terrace offset that puts V(q0) at the fraction @p phi of its
   * terrace above the level below. */
  double
  offset_at_fraction(const double V0, const double h, const double phi)
  {
    double c = V0 / h - std::floor(V0 / h) - phi;
    if (c < 0.)
      c += 1.;
    return c;
  }
} // namespace

TEST(Gravity, FreeFallWithEnergyStepping)
{
  const FreeFall fall;
  const Gravity &system = fall.system;
  const double   h      = 2e-3;
  // V(q0) in the middle of its terrace, far from the levels.
  const double          V0 = system.energy(fall.q0);
  const double          c  = offset_at_fraction(V0, h, 0.5);
  estep::EnergyStepping stepping(system, h, c);
  stepping.initialize(0., fall.q0, fall.v0);
  const long long L0           = stepping.terrace_index();
  const double    E0           = stepping.terraced_energy();
  const double    T0           = estep::kinetic_energy(system, fall.v0);
  const double    speed0       = std::sqrt(2. * T0 / fall.M);
  const double    T_end        = 1.;
  double          worst_energy = 0., worst_speed = 0., worst_elastic = 0.,
         worst_uniform = 0., worst_excursion = -1.;
  unsigned int n_descents = 0;
  long long    level      = L0;
  while (stepping.time() < T_end)
    {
      stepping.step(T_end);
      const Vector &q = stepping.position(), &v = stepping.velocity();
      const double  E = stepping.terraced_energy();
      const double  T = estep::kinetic_energy(system, v);
      worst_energy =
        std::max(worst_energy, std::abs(E - E0) / (std::abs(E0) + T));
      worst_elastic =
        std::max(worst_elastic, std::abs(system.base().energy(q)));
      worst_excursion =
        std::max(worst_excursion, estep_test::terrace_excursion(stepping, 8));
      // A rigid translation: every point moves with the centre of mass.
      const auto rigid = motion(system, q, v);
      for (unsigned int i = 0; i < v.size(); ++i)
        worst_uniform =
          std::max(worst_uniform, std::abs(v[i] - rigid.velocity[i % 3]));
      if (stepping.terrace_index() != level)
        {
          // Only descents: the speed after k of them.
          ASSERT_EQ(stepping.terrace_index(), level - 1);
          level = stepping.terrace_index();
          ++n_descents;
          const double k     = static_cast<double>(L0 - level);
          const double exact = std::sqrt(speed0 * speed0 + 2. * k * h / fall.M);
          const double speed = std::sqrt(rigid.velocity[0] * rigid.velocity[0] +
                                         rigid.velocity[1] * rigid.velocity[1] +
                                         rigid.velocity[2] * rigid.velocity[2]);
          worst_speed = std::max(worst_speed, std::abs(speed - exact) / exact);
          // The horizontal velocity is untouched.
          EXPECT_NEAR(rigid.velocity[0], 0.2, 1e-13);
          EXPECT_NEAR(rigid.velocity[1], 0., 1e-13);
        }
    }
  const auto counters = stepping.counters();
  std::cout << "free fall, h = " << h << ": " << stepping.n_steps()
            << " steps, " << n_descents << " descents; terraced energy drift "
            << worst_energy << ", speed after the descents: worst relative "
            << "error " << worst_speed << ", elastic energy at most "
            << worst_elastic << ", non-uniform velocity at most "
            << worst_uniform << ", largest excursion beyond a level "
            << worst_excursion << " h" << std::endl;
  for (const auto &[name, count] : counters)
    if (name == "climbs" || name == "reflections")
      {
        EXPECT_EQ(count, 0u) << name;
      }
  // The fall: 0.5 t + 9.81 t^2 / 2 over one second, in energy M g dz / h.
  EXPECT_GT(n_descents, 2000u);
  EXPECT_LT(worst_energy, 1e-13);
  EXPECT_LT(worst_speed, 1e-12);
  EXPECT_LT(worst_elastic, 1e-14);
  EXPECT_LT(worst_uniform, 1e-12);
  EXPECT_LT(worst_excursion, 1e-8);
}

TEST(Gravity, FreeFallTimeConvergesAtFirstOrder)
{
  // The time the centre of mass takes to fall by D = 1, for energy steps
  // halved five times, each with V(q0) at the same fraction phi of its
  // terrace above the level below (so that the error constant is the same
  // for every h).
  //
  // The leading error: after k descents the cube falls with the exact speed
  // u(k dz) of depth k dz (dz = h / (M g), the depth of a terrace), through
  // the depths [(k - 1 + phi) dz, (k + phi) dz], whose middle lies (1/2 -
  // phi) dz above k dz; summed over the terraces, t_h - t = (phi - 1/2) dz
  // (1 / u(0) - 1 / u(D)) + O(h^2). First order, except for phi = 1/2 (the
  // start in the middle of its terrace), where the first-order term cancels.
  const FreeFall fall;
  const double   depth = 1., exact = fall.exact_time(depth);
  const double   V0 = fall.system.energy(fall.q0);
  const double   u0 = -fall.v0[2];
  const double   uD = std::sqrt(u0 * u0 + 2. * standard_gravity * depth);
  const auto     fall_times = [&](const double phi) {
    std::vector<double> steps, errors;
    for (unsigned int k = 0; k < 6; ++k)
      {
        const double h = 1e-2 / std::pow(2., k);
        const double t = energy_stepping_fall_time(
          fall, h, offset_at_fraction(V0, h, phi), depth);
        steps.push_back(h);
        errors.push_back(t - exact);
        std::cout << "phi = " << phi << ", h = " << std::setw(10) << h
                  << ": fall time " << t << ", error " << t - exact
                  << std::endl;
      }
    return std::pair{steps, errors};
  };

  // A quarter of a terrace above the level below: first order.
  const auto [steps, errors] = fall_times(0.25);
  std::vector<double> magnitudes;
  for (const double e : errors)
    magnitudes.push_back(std::abs(e));
  const double rate    = estep_test::fitted_slope(steps, magnitudes);
  const double leading = (0.25 - 0.5) * steps.back() /
                         (fall.M * standard_gravity) * (1. / u0 - 1. / uD);
  std::cout << "exact fall time " << exact << ", fitted rate " << rate
            << "; at the finest h, error " << errors.back()
            << " against the leading term " << leading << std::endl;
  EXPECT_GE(rate, 0.8);
  EXPECT_LE(rate, 1.3);
  EXPECT_NEAR(errors.back(), leading, 0.05 * std::abs(leading));

  // In the middle of its terrace: the first-order term cancels.
  const auto [steps_middle, errors_middle] = fall_times(0.5);
  std::vector<double> magnitudes_middle;
  for (const double e : errors_middle)
    magnitudes_middle.push_back(std::abs(e));
  const double rate_middle =
    estep_test::fitted_slope(steps_middle, magnitudes_middle);
  std::cout << "from the middle of a terrace: fitted rate " << rate_middle
            << std::endl;
  EXPECT_GT(rate_middle, 1.7);
}

TEST(Gravity, ExplicitNewmarkFollowsTheParabola)
{
  const FreeFall         fall;
  estep::ExplicitNewmark newmark(fall.system, 1e-3);
  newmark.initialize(0., fall.q0, fall.v0);
  const auto start = motion(fall.system, fall.q0, fall.v0);
  double     worst = 0.;
  while (newmark.time() < 1.)
    {
      newmark.step(1.);
      const double t = newmark.time();
      const auto   m =
        motion(fall.system, newmark.position(), newmark.velocity());
      const double z =
        start.centre[2] - 0.5 * t - 0.5 * standard_gravity * t * t;
      const double x = start.centre[0] + 0.2 * t;
      worst =
        std::max({worst,
                  std::abs(m.centre[2] - z) / (std::abs(z) + 1.),
                  std::abs(m.centre[0] - x) / (std::abs(x) + 1.),
                  std::abs(m.velocity[2] - (-0.5 - standard_gravity * t)) /
                    (0.5 + standard_gravity * t)});
    }
  std::cout << "explicit Newmark, dt = 1e-3: " << newmark.n_steps()
            << " steps, worst relative deviation from the parabola " << worst
            << ", elastic energy "
            << fall.system.base().energy(newmark.position()) << std::endl;
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(std::abs(fall.system.base().energy(newmark.position())), 1e-14);
}
