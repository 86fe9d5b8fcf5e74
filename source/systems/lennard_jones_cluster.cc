#include <estep/systems/lennard_jones_cluster.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace
  {
    /** The pairs of a cluster along one free flight: u(s) = A + B s + C s^2 per
     * pair. */
    class LennardJonesFlight : public FreeFlight
    {
    public:
      LennardJonesFlight(const LennardJonesCluster &cluster,
                         const Vector              &q,
                         const Vector              &v,
                         const unsigned int         dim,
                         const double               sigma2)
        : cluster(cluster)
        , u_min(std::cbrt(2.) * sigma2)
        , u_inflection(std::cbrt(3.5) * sigma2)
      {
        const unsigned int n = q.size() / dim;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = i + 1; j < n; ++j)
            {
              Quadratic p{0., 0., 0.};
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const double r = q[dim * i + c] - q[dim * j + c];
                  const double w = v[dim * i + c] - v[dim * j + c];
                  p.A += r * r;
                  p.B += 2. * r * w;
                  p.C += w * w;
                }
              pairs.push_back(p);
            }
      }

      double
      value(const double s) const override
      {
        double sum = 0.;
        for (const Quadratic &p : pairs)
          sum += cluster.pair_energy(p.A + s * (p.B + s * p.C));
        return sum;
      }

      LineValue
      value_and_derivative(const double s) const override
      {
        LineValue result{0., 0.};
        for (const Quadratic &p : pairs)
          {
            const double u = p.A + s * (p.B + s * p.C);
            result.value += cluster.pair_energy(u);
            result.derivative +=
              cluster.pair_energy_derivative(u) * (p.B + 2. * s * p.C);
          }
        return result;
      }

      LineEnclosure
      enclose(const double a, const double b) const override
      {
        LineEnclosure result{{0., 0.}, {0., 0.}};
        double        magnitude = 0.;
        for (const Quadratic &p : pairs)
          {
            const Interval u = quadratic_range(p.A, p.B, p.C, a, b);
            const double   u_lo =
              std::max(u.lower, std::numeric_limits<double>::min());
            const double u_hi = u.upper;
            // phi decreases below u_min and increases above it.
            Interval phi = Interval::hull(cluster.pair_energy(u_lo),
                                          cluster.pair_energy(u_hi));
            if (u_lo < u_min && u_min < u_hi)
              phi.lower = cluster.pair_energy(u_min);
            // phi' increases below u_inflection and decreases above it.
            Interval dphi =
              Interval::hull(cluster.pair_energy_derivative(u_lo),
                             cluster.pair_energy_derivative(u_hi));
            if (u_lo < u_inflection && u_inflection < u_hi)
              dphi.upper = cluster.pair_energy_derivative(u_inflection);
            const Interval du =
              Interval::hull(p.B + 2. * a * p.C, p.B + 2. * b * p.C);
            result.value.lower += phi.lower;
            result.value.upper += phi.upper;
            result.derivative += dphi * du;
            magnitude += std::max(std::abs(phi.lower), std::abs(phi.upper));
          }
        // Round-off of the pair evaluations and of the sum.
        const double margin =
          64. * std::numeric_limits<double>::epsilon() * magnitude;
        result.value      = result.value.widened(0., margin);
        result.derivative = result.derivative.widened(
          64. * std::numeric_limits<double>::epsilon());
        return result;
      }

    private:
      struct Quadratic
      {
        double A, B, C;
      };
      const LennardJonesCluster &cluster;
      const double               u_min, u_inflection;
      std::vector<Quadratic>     pairs;
    };
  } // namespace



  LennardJonesCluster::LennardJonesCluster(const unsigned int dimension,
                                           const unsigned int n_particles,
                                           const double       mass,
                                           const double       epsilon,
                                           const double       sigma)
    : dim(dimension)
    , n_particles(n_particles)
    , epsilon(epsilon)
    , sigma2(sigma * sigma)
    , inverse_masses(dimension * n_particles)
  {
    if (dimension != 2 && dimension != 3)
      throw std::invalid_argument(
        "A Lennard-Jones cluster lives in 2 or 3 dimensions.");
    if (!(mass > 0.) || !(epsilon > 0.) || !(sigma > 0.))
      throw std::invalid_argument(
        "The mass, epsilon and sigma of a Lennard-Jones cluster must be positive.");
    inverse_masses = 1. / mass;
  }



  std::string
  LennardJonesCluster::name() const
  {
    return "lennard-jones cluster";
  }

  unsigned int
  LennardJonesCluster::spatial_dimension() const
  {
    return dim;
  }

  unsigned int
  LennardJonesCluster::n_dofs() const
  {
    return dim * n_particles;
  }

  const Vector &
  LennardJonesCluster::inverse_mass() const
  {
    return inverse_masses;
  }



  double
  LennardJonesCluster::pair_energy(const double u) const
  {
    const double x6 = sigma2 * sigma2 * sigma2 / (u * u * u);
    return 4. * epsilon * x6 * (x6 - 1.);
  }

  double
  LennardJonesCluster::pair_energy_derivative(const double u) const
  {
    const double x6 = sigma2 * sigma2 * sigma2 / (u * u * u);
    return 4. * epsilon * x6 * (3. - 6. * x6) / u;
  }



  double
  LennardJonesCluster::energy(const Vector &q) const
  {
    double sum = 0.;
    for (unsigned int i = 0; i < n_particles; ++i)
      for (unsigned int j = i + 1; j < n_particles; ++j)
        {
          double u = 0.;
          for (unsigned int c = 0; c < dim; ++c)
            {
              const double r = q[dim * i + c] - q[dim * j + c];
              u += r * r;
            }
          sum += pair_energy(u);
        }
    return sum;
  }



  void
  LennardJonesCluster::gradient(const Vector &q, Vector &g) const
  {
    g.reinit(q.size());
    for (unsigned int i = 0; i < n_particles; ++i)
      for (unsigned int j = i + 1; j < n_particles; ++j)
        {
          double r[3], u = 0.;
          for (unsigned int c = 0; c < dim; ++c)
            {
              r[c] = q[dim * i + c] - q[dim * j + c];
              u += r[c] * r[c];
            }
          // Equal and opposite pair forces along r: no net force or torque.
          const double factor = 2. * pair_energy_derivative(u);
          for (unsigned int c = 0; c < dim; ++c)
            {
              g[dim * i + c] += factor * r[c];
              g[dim * j + c] -= factor * r[c];
            }
        }
  }



  std::unique_ptr<FreeFlight>
  LennardJonesCluster::free_flight(const Vector &q, const Vector &v) const
  {
    return std::make_unique<LennardJonesFlight>(*this, q, v, dim, sigma2);
  }



  std::vector<std::string>
  LennardJonesCluster::observable_names() const
  {
    std::vector<std::string> names;
    const char               axes[] = {'x', 'y', 'z'};
    for (unsigned int i = 0; i < n_particles; ++i)
      for (unsigned int c = 0; c < dim; ++c)
        names.push_back(std::string(1, axes[c]) + std::to_string(i + 1));
    return names;
  }

  std::vector<double>
  LennardJonesCluster::observables(const Vector &q, const Vector &) const
  {
    return std::vector<double>(q.begin(), q.end());
  }
} // namespace estep
