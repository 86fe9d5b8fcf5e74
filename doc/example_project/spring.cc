// A mass on a linear spring, V(x) = k/2 |x|^2 in the plane, as a user-defined
// estep::MechanicalSystem, integrated by energy-stepping. Exits with 0 when the
// terraced energy is conserved and the orbit stays on the energy shell.
#include <estep/systems/mechanical_system.h>
#include <estep/time_integration/energy_stepping.h>

#include <cmath>
#include <iostream>

namespace
{
  /** V(q + s v) = k/2 (|q|^2 + 2 s q.v + s^2 |v|^2): a quadratic, enclosed
   * exactly. */
  class SpringFlight : public estep::FreeFlight
  {
  public:
    SpringFlight(const double k, const estep::Vector &q, const estep::Vector &v)
      : c0(0.5 * k * (q * q))
      , c1(k * (q * v))
      , c2(0.5 * k * (v * v))
    {}

    double
    value(const double s) const override
    {
      return c0 + s * (c1 + s * c2);
    }

    estep::LineValue
    value_and_derivative(const double s) const override
    {
      return {value(s), c1 + 2. * s * c2};
    }

    estep::LineEnclosure
    enclose(const double a, const double b) const override
    {
      return {estep::quadratic_range(c0, c1, c2, a, b),
              estep::Interval::hull(c1 + 2. * a * c2, c1 + 2. * b * c2)
                .widened(estep::interval_rounding)};
    }

  private:
    const double c0, c1, c2;
  };

  class Spring : public estep::MechanicalSystem
  {
  public:
    explicit Spring(const double k)
      : k(k)
      , inverse_masses(2)
    {
      inverse_masses = 1.;
    }

    std::string
    name() const override
    {
      return "spring";
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

    const estep::Vector &
    inverse_mass() const override
    {
      return inverse_masses;
    }

    double
    energy(const estep::Vector &q) const override
    {
      return 0.5 * k * (q * q);
    }

    void
    gradient(const estep::Vector &q, estep::Vector &g) const override
    {
      g = q;
      g *= k;
    }

    std::unique_ptr<estep::FreeFlight>
    free_flight(const estep::Vector &q, const estep::Vector &v) const override
    {
      return std::make_unique<SpringFlight>(k, q, v);
    }

  private:
    const double  k;
    estep::Vector inverse_masses;
  };
} // namespace

int
main()
{
  const Spring  spring(1.);
  estep::Vector q(2), v(2);
  q[0] = 1.;
  v[1] = 1.;
  estep::EnergyStepping stepping(spring, 1e-3);
  stepping.initialize(0., q, v);
  const double E0 = stepping.terraced_energy();
  while (stepping.time() < 10.)
    stepping.step(10.);
  const double drift  = std::abs(stepping.terraced_energy() - E0) / E0;
  const double radius = stepping.position().l2_norm();
  std::cout << "spring: " << stepping.n_steps()
            << " steps, terraced energy drift " << drift << ", radius "
            << radius << '\n';
  return (drift < 1e-12 && std::abs(radius - 1.) < 1e-2) ? 0 : 1;
}
