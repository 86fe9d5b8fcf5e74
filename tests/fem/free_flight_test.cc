// The free-flight view of the elastic body: values and slopes against the body,
// rigorous enclosures, and the first inversion.
#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>

#include <gtest/gtest.h>

#include "test_bodies.h"

#include <cmath>
#include <random>

namespace
{
  using estep_test::seed_cube;

  /** q + s v */
  estep::Vector
  along(const estep::Vector &q, const estep::Vector &v, const double s)
  {
    estep::Vector x = q;
    x.add(s, v);
    return x;
  }

  /** A deformed, moving state of the cube: spin plus random velocities. */
  void
  state(const estep::ElasticBody &body,
        estep::Vector            &q,
        estep::Vector            &v,
        const unsigned int        seed,
        const double              velocity_noise = 0.05)
  {
    q = estep_test::perturbed(body, 0.004, seed);
    v = body.rigid_velocity(q,
                            {{0.1, 0., 0.}},
                            {{0., 0., 1.}},
                            {{0.5, 0.5, 0.5}});
    v += estep_test::random_vector(body.n_dofs(), velocity_noise, seed + 100);
  }

  TEST(ElasticFreeFlight, ValueAndSlopeMatchBody)
  {
    const auto   &body = seed_cube();
    estep::Vector q, v;
    state(body, q, v, 21);
    const auto flight = body.free_flight(q, v);
    for (const double s : {0., 1e-3, 0.01, 0.05})
      {
        const double  V = body.energy(along(q, v, s));
        estep::Vector g;
        body.gradient(along(q, v, s), g);
        const double dV = g * v;
        EXPECT_NEAR(flight->value(s), V, 1e-13 * (1. + std::abs(V)))
          << "s = " << s;
        const auto lv = flight->value_and_derivative(s);
        EXPECT_NEAR(lv.value, V, 1e-13 * (1. + std::abs(V)));
        EXPECT_NEAR(lv.derivative, dV, 1e-10 * (1. + std::abs(dV)))
          << "s = " << s;
        // Slope against central differences of the flight itself.
        const double h = 1e-5;
        EXPECT_NEAR(lv.derivative,
                    (flight->value(s + h) - flight->value(s - h)) / (2. * h),
                    1e-7 * (1. + std::abs(dV)));
      }
  }

  TEST(ElasticFreeFlight, UndeformedAtRestStartIsZero)
  {
    const auto         &body = seed_cube();
    const estep::Vector q    = body.reference_configuration();
    const estep::Vector v =
      body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, {{0.5, 0.5, 0.5}});
    const auto flight = body.free_flight(q, v);
    EXPECT_NEAR(flight->value(0.), 0., 1e-15);
    // A rigid rotation never inverts an element: J_e(s) = 1 + s^2 per cell.
    EXPECT_TRUE(std::isinf(flight->admissible_limit()) ||
                flight->admissible_limit() > 1e6);
  }

  TEST(ElasticFreeFlight, EnclosuresContainSamples)
  {
    const auto   &body = seed_cube();
    estep::Vector q, v;
    // Moderate velocities, and violent ones (large velocity gradients, whose
    // determinant is the cubic term of J(s) along the flight).
    for (const double noise : {0.3, 5.})
      {
        state(body, q, v, 22, noise);
        const auto   flight = body.free_flight(q, v);
        const double limit  = flight->admissible_limit();
        ASSERT_GT(limit, 0.);
        const double                           horizon = std::min(limit, 0.5);
        std::mt19937                           rng(5);
        std::uniform_real_distribution<double> u(0., horizon);
        for (unsigned int k = 0; k < 40; ++k)
          {
            double a = u(rng), b = u(rng);
            if (a > b)
              std::swap(a, b);
            if (k % 4 == 0)
              b = a + 1e-6 * horizon; // narrow
            const auto enclosure = flight->enclose(a, b);
            EXPECT_LE(enclosure.value.lower, enclosure.value.upper);
            // Its sample (computed in the pass that encloses the curvature)
            // is f and f' at the centre, within the flight's round-off.
            ASSERT_GE(enclosure.sample_point, a);
            ASSERT_LE(enclosure.sample_point, b);
            const auto centre =
              flight->value_and_derivative(enclosure.sample_point);
            EXPECT_NEAR(enclosure.sample.value,
                        centre.value,
                        flight->value_tolerance());
            EXPECT_NEAR(enclosure.sample.derivative,
                        centre.derivative,
                        1e-12 * (1. + std::abs(centre.derivative)));
            for (unsigned int m = 0; m <= 20; ++m)
              {
                const double s  = a + (b - a) * m / 20.;
                const auto   lv = flight->value_and_derivative(s);
                EXPECT_TRUE(enclosure.value.contains(lv.value))
                  << "[" << a << ", " << b << "] s = " << s << " " << lv.value
                  << " not in [" << enclosure.value.lower << ", "
                  << enclosure.value.upper << "]";
                EXPECT_TRUE(enclosure.value.contains(flight->value(s)));
                EXPECT_TRUE(enclosure.derivative.contains(lv.derivative))
                  << "[" << a << ", " << b << "] s = " << s;
                // f'' by central differences of f' (error about 1e-8 of the
                // curvature's scale), inside the curvature enclosure.
                const double delta = 1e-5 * horizon;
                if (k % 4 != 0 && s - delta > a && s + delta < b)
                  {
                    const double curvature =
                      (flight->value_and_derivative(s + delta).derivative -
                       flight->value_and_derivative(s - delta).derivative) /
                      (2. * delta);
                    const double slack =
                      1e-6 * (std::abs(enclosure.curvature.lower) +
                              std::abs(enclosure.curvature.upper));
                    EXPECT_GE(curvature, enclosure.curvature.lower - slack)
                      << "[" << a << ", " << b << "] s = " << s;
                    EXPECT_LE(curvature, enclosure.curvature.upper + slack)
                      << "[" << a << ", " << b << "] s = " << s;
                  }
              }
            // Narrow intervals give narrow enclosures.
            if (k % 4 == 0)
              {
                EXPECT_LT(enclosure.value.width(),
                          1e-3 * (std::abs(enclosure.value.lower) + 1e-12) +
                            1e-9);
              }
          }
      }

    // A point interval is tight.
    state(body, q, v, 22, 0.3);
    const auto   flight = body.free_flight(q, v);
    const auto   point  = flight->enclose(0.01, 0.01);
    const double V      = flight->value(0.01);
    EXPECT_TRUE(point.value.contains(V));
    EXPECT_LT(point.value.width(), 1e-9 * std::abs(V) + 1e-13);
  }

  TEST(ElasticFreeFlight, AdmissibleLimitIsFirstInversionFromBelow)
  {
    const auto &body = seed_cube();
    for (unsigned int seed = 0; seed < 3; ++seed)
      {
        // Strong random velocities: elements invert soon.
        estep::Vector q = estep_test::perturbed(body, 0.004, 30 + seed);
        estep::Vector v =
          estep_test::random_vector(body.n_dofs(), 1., 40 + seed);
        const auto   flight = body.make_free_flight(q, v);
        const double limit  = flight->admissible_limit();
        ASSERT_TRUE(std::isfinite(limit));
        ASSERT_GT(limit, 0.);
        // Every J_e is positive on [0, limit] (dense sampling) ...
        const auto &d                 = body.cell_data();
        double      first_nonpositive = std::numeric_limits<double>::infinity();
        for (unsigned int e = 0; e < d.n_cells; ++e)
          {
            const auto c = flight->jacobian_cubic(e);
            const auto J = [&](const double s) {
              return c[0] + s * (c[1] + s * (c[2] + s * c[3]));
            };
            for (unsigned int m = 0; m <= 200; ++m)
              {
                const double s = 1.05 * limit * m / 200.;
                if (J(s) <= 0.)
                  {
                    first_nonpositive = std::min(first_nonpositive, s);
                    break;
                  }
              }
            EXPECT_GT(J(limit), 0.);
          }
        EXPECT_GE(first_nonpositive, limit);
        // ... and some element inverts just after: the limit is tight.
        EXPECT_TRUE(std::isinf(flight->value(limit * (1. + 1e-9))))
          << "the limit " << limit << " is too early";
        // The energy just below it is finite (and agrees with the body).
        const double s = limit * (1. - 1e-9);
        EXPECT_TRUE(std::isfinite(flight->value(s)));
        EXPECT_TRUE(std::isfinite(body.energy(along(q, v, 0.999 * limit))));
        EXPECT_TRUE(std::isinf(body.energy(along(q, v, 1.001 * limit))));
      }
  }
} // namespace
