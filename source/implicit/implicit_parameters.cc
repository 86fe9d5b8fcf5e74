#include <deal.II/base/parameter_handler.h>

#include <estep/base/parameter_subsections.h>
#include <estep/implicit/implicit_parameters.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace estep
{
  void
  ImplicitParameters::check() const
  {
    const auto require = [](const bool ok, const std::string &message) {
      if (!ok)
        throw std::invalid_argument("Time integration/Implicit integrators: " +
                                    message);
    };
    require(time_step > 0. && std::isfinite(time_step),
            "the time step must be positive.");
    require(relative_tolerance > 0. && absolute_tolerance > 0.,
            "the relative and absolute tolerances must be positive.");
    require(maximum_bdf_order >= 1 && maximum_bdf_order <= 5,
            "the maximum BDF order must be in 1..5.");
    require(arkode_order >= 2 && arkode_order <= 5,
            "the ARKode order must be in 2..5.");
    require(newton_tolerance > 0., "the Newton tolerance must be positive.");
    require(maximum_newton_iterations >= 1,
            "the maximum number of Newton iterations must be at least 1.");
    require(jacobian_update_interval >= 1,
            "the Jacobian update interval must be at least 1.");
    require(minimum_step >= 0., "the minimum step must not be negative.");
    require(linear_tolerance > 0. && linear_tolerance < 1.,
            "the linear tolerance must be in (0, 1).");
  }

  void
  ImplicitParameters::check_adaptive() const
  {
    check();
    if (minimum_step > time_step)
      {
        std::ostringstream message;
        message << "Time integration/Implicit integrators/Minimum step: "
                << minimum_step << " exceeds the initial step of the adaptive "
                << "methods (Time step = " << time_step
                << "); it must be at most that.";
        throw std::invalid_argument(message.str());
      }
  }

  std::string
  to_string(const ImplicitLinearSolver solver)
  {
    return solver == ImplicitLinearSolver::direct ? "direct" : "cg amg";
  }

  void
  declare_implicit_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Selection;
    const ImplicitParameters d;
    prm.enter_subsection("Implicit integrators");
    prm.declare_entry(
      "Time step",
      "1e-3",
      Double(0., Double::max_double_value),
      "The fixed time step of arkode midpoint and energy momentum (at "
      "least about a million units of round-off of the End time); the "
      "initial step of the adaptive methods (ida bdf, arkode irk).");
    prm.declare_entry(
      "Relative tolerance",
      "1e-6",
      Double(1e-14, 1.),
      "Relative local error tolerance of the adaptive methods (ida bdf, "
      "arkode irk).");
    prm.declare_entry(
      "Absolute tolerance",
      "1e-8",
      Double(1e-300, 1e10),
      "Absolute local error tolerance of the adaptive methods, in the units of "
      "the positions and velocities.");
    prm.declare_entry("Maximum BDF order",
                      std::to_string(d.maximum_bdf_order),
                      Integer(1, 5),
                      "Maximum order of the variable-order BDF of ida bdf.");
    prm.declare_entry("ARKode order",
                      std::to_string(d.arkode_order),
                      Integer(2, 5),
                      "Order of the adaptive DIRK method of arkode irk "
                      "(ARKode's default table of that order).");
    prm.declare_entry(
      "Newton tolerance",
      "1e-10",
      Double(1e-15, 1e-1),
      "Tolerance of the nonlinear solves of the fixed-step methods: arkode "
      "midpoint (relative and absolute tolerance of ARKode's Newton test) and "
      "energy momentum (max-norm of the velocity residual relative to "
      "1 + max |v|; never below the residual's round-off, 16 eps (2/dt) "
      "max |q|, eps the machine epsilon). It bounds their energy and "
      "momentum errors.");
    prm.declare_entry("Maximum Newton iterations",
                      std::to_string(d.maximum_newton_iterations),
                      Integer(1, 1000),
                      "Maximum Newton iterations per nonlinear solve (per "
                      "stage or step); a solve that needs more fails.");
    prm.declare_entry(
      "Jacobian update interval",
      std::to_string(d.jacobian_update_interval),
      Integer(1, 1000),
      "ARKode methods: maximum number of steps between two setups of the "
      "Newton matrix (assembly of the tangent stiffness and factorisation).");
    prm.declare_entry(
      "Minimum step",
      "1e-8",
      Double(0., 1e10),
      "Smallest step the adaptive methods may take; a step-size collapse "
      "below it ends the run (status unstable, with a message).");
    prm.declare_entry(
      "Linear solver",
      "direct",
      Selection("direct|cg amg"),
      "Solver of the Newton systems (a M + H) x = b: direct (sparse LU, "
      "UMFPACK) or cg amg (Trilinos CG with ML algebraic multigrid; needs "
      "MPI initialised).");
    prm.declare_entry("Linear tolerance",
                      "1e-10",
                      Double(1e-16, 0.5),
                      "cg amg: relative residual tolerance of CG.");
    prm.declare_entry("Maximum linear iterations",
                      std::to_string(d.maximum_linear_iterations),
                      Integer(1, 100000),
                      "cg amg: maximum CG iterations per linear solve.");
    prm.leave_subsection();
  }

  ImplicitParameters
  parse_implicit_parameters(const dealii::ParameterHandler &prm_const)
  {
    // ParameterHandler::enter_subsection is not const.
    auto              &prm = const_cast<dealii::ParameterHandler &>(prm_const);
    ImplicitParameters p;
    prm.enter_subsection("Implicit integrators");
    p.time_step                 = prm.get_double("Time step");
    p.relative_tolerance        = prm.get_double("Relative tolerance");
    p.absolute_tolerance        = prm.get_double("Absolute tolerance");
    p.maximum_bdf_order         = prm.get_integer("Maximum BDF order");
    p.arkode_order              = prm.get_integer("ARKode order");
    p.newton_tolerance          = prm.get_double("Newton tolerance");
    p.maximum_newton_iterations = prm.get_integer("Maximum Newton iterations");
    p.jacobian_update_interval  = prm.get_integer("Jacobian update interval");
    p.minimum_step              = prm.get_double("Minimum step");
    p.linear_solver             = prm.get("Linear solver") == "direct" ?
                                    ImplicitLinearSolver::direct :
                                    ImplicitLinearSolver::cg_amg;
    p.linear_tolerance          = prm.get_double("Linear tolerance");
    p.maximum_linear_iterations = prm.get_integer("Maximum linear iterations");
    prm.leave_subsection();
    p.check();

    // The entries that only some of the methods, or only CG, read.
    const std::string section = "Time integration/Implicit integrators";
    const std::vector<std::string> adaptive = {"arkode irk", "ida bdf"};
    p.unread_entries                        = entries_unread_by_type(
      prm,
      {{section,
                               {{"Relative tolerance", adaptive},
                                {"Absolute tolerance", adaptive},
                                {"Minimum step", adaptive},
                                {"Maximum BDF order", {"ida bdf"}},
                                {"ARKode order", {"arkode irk"}},
                                {"Newton tolerance", {"arkode midpoint", "energy momentum"}},
                                {"Jacobian update interval", {"arkode irk", "arkode midpoint"}}},
                               "Time integration/Method"},
                              {section,
                               {{"Linear tolerance", {"cg amg"}},
                                {"Maximum linear iterations", {"cg amg"}}},
                               section + "/Linear solver"}});
    return p;
  }
} // namespace estep
