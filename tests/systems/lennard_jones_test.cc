// The Lennard-Jones cluster against oracles written independently here: the
// energy against the pair sum 4 epsilon ((sigma/r)^12 - (sigma/r)^6) over all
// pairs (the class documents no cutoff and no shift), the gradient against
// central differences of the energy, and the free flight against the energy
// and gradient along its line.
#include <estep/systems/lennard_jones_cluster.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

namespace
{
  using estep::LennardJonesCluster;
  using estep::Vector;

  /** The parameters of a test cluster. */
  struct Cluster
  {
    unsigned int dim, n;
    double       mass, epsilon, sigma;
  };

  /**
   * @p c.n particles at random points of a box, no two closer than 0.85
   * sigma, so that every pair is well inside the region where double
   * precision resolves the potential.
   */
  Vector
  random_configuration(const Cluster &c, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(0., 2.2 * c.sigma);
    Vector                                 q(c.dim * c.n);
    for (unsigned int i = 0; i < c.n;)
      {
        for (unsigned int d = 0; d < c.dim; ++d)
          q[c.dim * i + d] = u(rng);
        bool far_enough = true;
        for (unsigned int j = 0; j < i; ++j)
          {
            double r2 = 0.;
            for (unsigned int d = 0; d < c.dim; ++d)
              r2 += std::pow(q[c.dim * i + d] - q[c.dim * j + d], 2);
            far_enough = far_enough && std::sqrt(r2) > 0.85 * c.sigma;
          }
        if (far_enough)
          ++i;
      }
    return q;
  }

  /** The documented energy, as a plain sum over pairs of distances. */
  double
  pair_sum(const Cluster &c, const Vector &q)
  {
    double sum = 0.;
    for (unsigned int i = 0; i < c.n; ++i)
      for (unsigned int j = 0; j < i; ++j)
        {
          double r2 = 0.;
          for (unsigned int d = 0; d < c.dim; ++d)
            r2 += std::pow(q[c.dim * i + d] - q[c.dim * j + d], 2);
          const double s6 = std::pow(c.sigma / std::sqrt(r2), 6);
          sum += 4. * c.epsilon * (s6 * s6 - s6);
        }
    return sum;
  }

  const Cluster clusters[] = {{3, 7, 1.7, 1.3, 0.9}, {2, 6, 0.4, 0.8, 1.2}};

  TEST(LennardJones, EnergyIsThePairSum)
  {
    for (const Cluster &c : clusters)
      {
        const LennardJonesCluster cluster(
          c.dim, c.n, c.mass, c.epsilon, c.sigma);
        EXPECT_EQ(cluster.n_dofs(), c.dim * c.n);
        EXPECT_EQ(cluster.spatial_dimension(), c.dim);
        for (const double m_inv : cluster.inverse_mass())
          EXPECT_DOUBLE_EQ(m_inv, 1. / c.mass);
        for (unsigned int seed = 1; seed <= 5; ++seed)
          {
            const Vector q     = random_configuration(c, seed);
            const double exact = pair_sum(c, q);
            EXPECT_NEAR(cluster.energy(q),
                        exact,
                        1e-12 * (1. + std::abs(exact)))
              << "dim " << c.dim << ", seed " << seed;
          }
      }
  }

  TEST(LennardJones, PairPotentialMinimumAndZero)
  {
    const double              epsilon = 1.3, sigma = 0.9;
    const LennardJonesCluster cluster(3, 2, 1., epsilon, sigma);
    // phi(sigma) = 0, and the minimum -epsilon at r = 2^(1/6) sigma.
    const double u_zero = sigma * sigma;
    const double u_min  = std::pow(2., 1. / 3.) * sigma * sigma;
    EXPECT_NEAR(cluster.pair_energy(u_zero), 0., 1e-14);
    EXPECT_NEAR(cluster.pair_energy(u_min), -epsilon, 1e-14);
    EXPECT_NEAR(cluster.pair_energy_derivative(u_min), 0., 1e-13);
    // d phi / du against central differences in u.
    for (const double u : {0.7, 0.81, 1.1, 2.5, 6.})
      {
        const double du = 1e-6 * u;
        const double fd =
          (cluster.pair_energy(u + du) - cluster.pair_energy(u - du)) /
          (2. * du);
        EXPECT_NEAR(cluster.pair_energy_derivative(u),
                    fd,
                    1e-7 * std::abs(fd) + 1e-10)
          << "u = " << u;
      }
  }

  /**
   * The gradient against central differences of the energy, coordinate by
   * coordinate. With the step 1e-5 sigma the difference quotient is accurate
   * to about 1e-9 relative; the test allows 1e-6 of the largest component,
   * while an error of a constant factor (a halved gradient) is off by 50 %.
   */
  TEST(LennardJones, GradientMatchesCentralDifferencesOfEnergy)
  {
    for (const Cluster &c : clusters)
      {
        const LennardJonesCluster cluster(
          c.dim, c.n, c.mass, c.epsilon, c.sigma);
        for (unsigned int seed = 1; seed <= 5; ++seed)
          {
            const Vector q = random_configuration(c, seed);
            Vector       g;
            cluster.gradient(q, g);
            ASSERT_EQ(g.size(), q.size());
            const double delta = 1e-5 * c.sigma;
            double       error = 0.;
            Vector       qp(q);
            for (unsigned int k = 0; k < q.size(); ++k)
              {
                qp[k]           = q[k] + delta;
                const double Ep = cluster.energy(qp);
                qp[k]           = q[k] - delta;
                const double Em = cluster.energy(qp);
                qp[k]           = q[k];
                error =
                  std::max(error, std::abs(g[k] - (Ep - Em) / (2. * delta)));
              }
            std::cout << "dim " << c.dim << ", seed " << seed
                      << ": gradient error / max |g| = "
                      << error / g.linfty_norm() << '\n';
            EXPECT_LT(error, 1e-6 * g.linfty_norm())
              << "dim " << c.dim << ", seed " << seed << ", |g| "
              << g.linfty_norm();
            EXPECT_GT(g.linfty_norm(), 1e-2 * c.epsilon / c.sigma);

            // Pair forces are equal and opposite: no net force.
            for (unsigned int d = 0; d < c.dim; ++d)
              {
                double total = 0.;
                for (unsigned int i = 0; i < c.n; ++i)
                  total += g[c.dim * i + d];
                EXPECT_NEAR(total, 0., 1e-12 * g.linfty_norm());
              }
          }
      }
  }

  /** The gradient overwrites whatever the output vector held. */
  TEST(LennardJones, GradientResetsItsOutput)
  {
    const Cluster             c = clusters[0];
    const LennardJonesCluster cluster(c.dim, c.n, c.mass, c.epsilon, c.sigma);
    const Vector              q = random_configuration(c, 3);
    Vector                    g, g_dirty(q.size());
    cluster.gradient(q, g);
    g_dirty = 17.;
    cluster.gradient(q, g_dirty);
    g_dirty -= g;
    EXPECT_EQ(g_dirty.linfty_norm(), 0.);
  }

  /**
   * The free flight along q + s v: its values and slopes are the energy and
   * the directional derivative grad V . v there, and its enclosures hold the
   * values and slopes sampled densely inside them.
   */
  TEST(LennardJones, FreeFlightMatchesEnergyAndGradient)
  {
    for (const Cluster &c : clusters)
      {
        const LennardJonesCluster cluster(
          c.dim, c.n, c.mass, c.epsilon, c.sigma);
        const Vector                           q = random_configuration(c, 11);
        std::mt19937                           rng(4);
        std::uniform_real_distribution<double> u(-1., 1.);
        Vector                                 v(q.size());
        for (auto &x : v)
          x = 0.3 * u(rng);
        const auto flight = cluster.free_flight(q, v);
        Vector     x(q.size()), g;
        for (const double s : {0., 0.01, 0.05, 0.1})
          {
            x = q;
            x.add(s, v);
            cluster.gradient(x, g);
            const double V     = cluster.energy(x);
            const double slope = g * v;
            EXPECT_NEAR(flight->value(s), V, 1e-12 * (1. + std::abs(V)));
            const estep::LineValue both = flight->value_and_derivative(s);
            EXPECT_NEAR(both.value, V, 1e-12 * (1. + std::abs(V)));
            EXPECT_NEAR(both.derivative, slope, 1e-10 * (1. + std::abs(slope)))
              << "s = " << s;
          }
        for (const auto &[a, b] : {std::pair{0., 0.02}, std::pair{0.03, 0.1}})
          {
            const estep::LineEnclosure e = flight->enclose(a, b);
            for (unsigned int k = 0; k <= 64; ++k)
              {
                const double           s = a + (b - a) * k / 64.;
                const estep::LineValue f = flight->value_and_derivative(s);
                EXPECT_TRUE(e.value.contains(f.value)) << "s = " << s;
                EXPECT_TRUE(e.derivative.contains(f.derivative)) << "s = " << s;
              }
          }
      }
  }

  /**
   * Enclosures over intervals across the well and the inflection of the pair
   * potential: two particles approach head-on from 1.6 sigma to 0.95 sigma
   * (through u** = 3.5^(1/3) sigma^2, where phi' is largest, and u* =
   * 2^(1/3) sigma^2, where phi is smallest) while a third drifts by. Every
   * interval of several widths along the flight must hold the values and
   * slopes sampled inside it: enclosures that only look at the ends of an
   * interval miss the extremes in between.
   */
  TEST(LennardJones, EnclosuresHoldAcrossTheWellAndTheInflection)
  {
    const double              epsilon = 1.3, sigma = 0.9;
    const LennardJonesCluster cluster(3, 3, 1., epsilon, sigma);
    Vector                    q(9), v(9);
    q[3] = 1.6 * sigma; // particle 1 on the x axis
    q[6] = -1.5 * sigma, q[7] = 2. * sigma, q[8] = 0.3 * sigma;
    v[0] = 0.4, v[3] = -0.25; // closing speed 0.65, about 1 sigma per time
    v[6] = 0.1, v[7] = -0.2, v[8] = 0.05;
    const auto   flight    = cluster.free_flight(q, v);
    const double s_end     = 0.65 * sigma / 0.65; // r from 1.6 to 0.95 sigma
    unsigned int n_checked = 0;
    for (const double width : {0.05, 0.1, 0.2, 0.4})
      for (double a = 0.; a + width <= s_end; a += 0.5 * width)
        {
          const estep::LineEnclosure e = flight->enclose(a, a + width);
          for (unsigned int k = 0; k <= 200; ++k)
            {
              const double           s = a + width * k / 200.;
              const estep::LineValue f = flight->value_and_derivative(s);
              EXPECT_TRUE(e.value.contains(f.value))
                << "[" << a << ", " << a + width << "], s = " << s;
              EXPECT_TRUE(e.derivative.contains(f.derivative))
                << "[" << a << ", " << a + width << "], s = " << s;
              ++n_checked;
            }
        }
    EXPECT_GT(n_checked, 1000u);
  }
} // namespace
