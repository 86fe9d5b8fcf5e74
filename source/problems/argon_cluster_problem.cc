#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <estep/problems/problem.h>
#include <estep/systems/lennard_jones_cluster.h>

#include <cmath>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double boltzmann_constant = 1.380649e-23; // J/K

    /** Parse "x, y; x, y; ..." into points of @p dim coordinates. */
    std::vector<double>
    parse_points(const std::string &text,
                 const unsigned int dim,
                 const std::string &entry)
    {
      std::vector<double> values;
      for (const std::string &point :
           dealii::Utilities::split_string_list(text, ';'))
        {
          const std::vector<std::string> coordinates =
            dealii::Utilities::split_string_list(point, ',');
          if (coordinates.size() != dim)
            throw std::runtime_error(
              "Argon cluster/" + entry + ": the point <" + point +
              "> does not have " + std::to_string(dim) + " coordinates.");
          for (const std::string &x : coordinates)
            values.push_back(dealii::Utilities::string_to_double(x));
        }
      return values;
    }



    void
    declare_argon_cluster_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::List;
      prm.enter_subsection("Argon cluster");
      {
        prm.declare_entry("Dimension",
                          "2",
                          Integer(2, 3),
                          "Dimension of the space the atoms move in.");
        prm.declare_entry("Particle mass",
                          "66.34e-27",
                          Double(0.,
                                 dealii::Patterns::Double::max_double_value),
                          "Mass of one atom [kg]. The run's unit of mass.");
        prm.declare_entry(
          "Epsilon over Boltzmann constant",
          "119.8",
          Double(0.),
          "Depth epsilon of the Lennard-Jones well divided by the "
          "Boltzmann constant [K]. The run's unit of energy is epsilon.");
        prm.declare_entry(
          "Sigma",
          "0.341",
          Double(0.),
          "Lennard-Jones length sigma [nm]. The run's unit of length.");
        prm.declare_entry(
          "Initial positions",
          "0.00, 0.00; 0.02, 0.39; 0.34, 0.17; 0.36, -0.21; -0.02, -0.40; "
          "-0.35, -0.16; -0.31, 0.21",
          List(List(Double(), 2, 3, ","), 2, List::max_int_value, ";"),
          "Initial positions of the atoms [nm]: points separated by ';', coordinates by ','.");
        prm.declare_entry(
          "Initial velocities",
          "-30, -20; 50, -90; -70, -60; 90, 40; 80, 90; -40, 100; -80, -60",
          List(List(Double(), 2, 3, ","), 2, List::max_int_value, ";"),
          "Initial velocities of the atoms [m/s], in the order of the positions.");
      }
      prm.leave_subsection();
    }



    Problem
    create_argon_cluster_problem(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Argon cluster");
      const unsigned int dim  = prm.get_integer("Dimension");
      const double       mass = prm.get_double("Particle mass");
      const double       eps =
        boltzmann_constant * prm.get_double("Epsilon over Boltzmann constant");
      const double              sigma = 1e-9 * prm.get_double("Sigma");
      const std::vector<double> x_nm =
        parse_points(prm.get("Initial positions"), dim, "Initial positions");
      const std::vector<double> v_si =
        parse_points(prm.get("Initial velocities"), dim, "Initial velocities");
      prm.leave_subsection();
      for (const auto &[entry, value] :
           {std::pair{"Particle mass", mass},
            std::pair{"Epsilon over Boltzmann constant", eps},
            std::pair{"Sigma", sigma}})
        if (!(value > 0.))
          throw std::runtime_error(std::string("Argon cluster/") + entry +
                                   ": must be positive.");
      if (x_nm.size() != v_si.size())
        throw std::runtime_error(
          "Argon cluster: there are " + std::to_string(x_nm.size() / dim) +
          " initial positions but " + std::to_string(v_si.size() / dim) +
          " initial velocities.");

      const double       tau = sigma * std::sqrt(mass / eps);
      Problem            problem;
      const unsigned int n_atoms = x_nm.size() / dim;
      problem.system =
        std::make_unique<LennardJonesCluster>(dim, n_atoms, 1., 1., 1.);
      problem.q0.reinit(x_nm.size());
      problem.v0.reinit(v_si.size());
      for (unsigned int i = 0; i < x_nm.size(); ++i)
        {
          problem.q0[i] = 1e-9 * x_nm[i] / sigma;
          problem.v0[i] = v_si[i] * tau / sigma;
        }
      problem.description.add("atoms", n_atoms)
        .add("units", "reduced: length sigma, energy epsilon, mass m, time tau")
        .add("sigma [m]", sigma)
        .add("epsilon [J]", eps)
        .add("mass [kg]", mass)
        .add("tau [s]", tau);
      return problem;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_PROBLEM(
  "argon cluster",
  "Atoms of argon interacting by the Lennard-Jones potential in reduced units "
  "(subsection Argon cluster); the reference text's frozen cluster of seven "
  "atoms by default.",
  estep::declare_argon_cluster_parameters,
  estep::create_argon_cluster_problem)
