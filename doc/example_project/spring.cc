// A user's own problem as an estep plugin: a unit mass on a linear spring,
// V(x) = k/2 |x|^2 in the plane, written as an estep::MechanicalSystem and
// registered as the problem "spring". Built as a shared library (see
// CMakeLists.txt) and named in the input file's `Additional shared
// libraries`, it runs through the estep command with every integrator,
// postprocessor and output of the built-in problems: estep spring.prm.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <estep/problems/problem.h>
#include <estep/systems/mechanical_system.h>

#include <cmath>
#include <stdexcept>

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

    /** The distance from the origin, a column of history.csv. */
    std::vector<std::string>
    observable_names() const override
    {
      return {"radius"};
    }

    std::vector<double>
    observables(const estep::Vector &q, const estep::Vector &) const override
    {
      return {q.l2_norm()};
    }

  private:
    const double  k;
    estep::Vector inverse_masses;
  };

  /** The parameters of the problem, in its own subsection. */
  void
  declare_spring_parameters(dealii::ParameterHandler &prm)
  {
    const double max = dealii::Patterns::Double::max_double_value;
    const dealii::Patterns::List point(dealii::Patterns::Double(-max, max),
                                       2,
                                       2,
                                       ",");
    prm.enter_subsection("Spring");
    prm.declare_entry("Stiffness",
                      "1",
                      dealii::Patterns::Double(0., max),
                      "The spring constant k; must be positive.");
    prm.declare_entry("Initial position", "1, 0", point, "x(0).");
    prm.declare_entry("Initial velocity", "0, 1", point, "x'(0).");
    prm.leave_subsection();
  }

  estep::Vector
  parse_point(const std::string &text)
  {
    const auto    parts = dealii::Utilities::split_string_list(text, ',');
    estep::Vector x(2);
    for (unsigned int i = 0; i < 2; ++i)
      x[i] = dealii::Utilities::string_to_double(parts[i]);
    return x;
  }

  estep::Problem
  create_spring_problem(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Spring");
    const double k = prm.get_double("Stiffness");
    if (!(k > 0.))
      throw std::runtime_error("Spring/Stiffness: must be positive.");
    estep::Problem problem;
    problem.q0 = parse_point(prm.get("Initial position"));
    problem.v0 = parse_point(prm.get("Initial velocity"));
    prm.leave_subsection();
    problem.system = std::make_unique<Spring>(k);
    problem.description.add("stiffness", k);
    return problem;
  }
} // namespace

ESTEP_REGISTER_PROBLEM("spring",
                       "a unit mass on a linear spring in the plane "
                       "(subsection Spring): the example plugin.",
                       declare_spring_parameters,
                       create_spring_problem)
