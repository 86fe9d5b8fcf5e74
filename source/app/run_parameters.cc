#include <deal.II/base/parameter_handler.h>

#include <estep/app/run_parameters.h>
#include <estep/implicit/create_implicit_integrator.h>
#include <estep/implicit/implicit_parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  void
  RunParameters::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Selection;
    const double max = Double::max_double_value;

    prm.declare_entry(
      "Output directory",
      "output",
      dealii::Patterns::DirectoryName(),
      "Directory the run writes to (created if needed): parameters.prm, "
      "history.csv, step_histogram.csv and summary.json.");

    prm.enter_subsection("Time integration");
    {
      prm.declare_entry(
        "Method",
        "energy stepping",
        Selection("energy stepping|explicit newmark|" +
                  implicit_method_names()),
        "Time integrator: energy stepping (exact flow of the terraced "
        "potential h floor(V/h)); explicit newmark (beta = 0, gamma = 1/2, "
        "velocity Verlet); and the implicit comparison methods of SUNDIALS "
        "(elastic bodies): ida bdf (variable-step BDF), arkode midpoint "
        "(implicit midpoint rule at the fixed time step), arkode irk (adaptive "
        "diagonally implicit Runge-Kutta), energy momentum (discrete-gradient "
        "scheme solved by KINSOL at the fixed time step). See the subsection "
        "Implicit integrators.");
      prm.declare_entry("Start time", "0", Double(-max, max), "Initial time.");
      prm.declare_entry("End time",
                        "1",
                        Double(-max, max),
                        "Final time; must exceed the start time.");
      prm.declare_entry(
        "Energy step",
        "1e-3",
        Double(0., max),
        "Energy step h of energy stepping (energy units of the system). "
        "The time steps follow from it.");
      prm.declare_entry(
        "Terrace offset",
        "0",
        Double(0., 1.),
        "Where the levels of energy stepping lie, as a fraction c of the "
        "energy step: at (k + c) h for every integer k. This is the "
        "additive constant of V that the method leaves free; 0 puts the "
        "levels at the integer multiples of h. Must be smaller than 1.");
      prm.declare_entry("Time step",
                        "1e-3",
                        Double(0., max),
                        "Time step of explicit newmark, arkode midpoint and "
                        "energy momentum; the initial step of the adaptive "
                        "implicit methods.");
      prm.declare_entry(
        "Blow-up factor",
        "1e3",
        Double(1., max),
        "A run stops with status unstable when its kinetic energy exceeds "
        "this factor times the initial |T| + |V|.");
    }
    prm.leave_subsection();

    declare_implicit_parameters(prm);

    prm.enter_subsection("Output");
    {
      prm.declare_entry(
        "History interval",
        "0.1",
        Double(0., max),
        "Write a row of history.csv every this much simulated time, from "
        "the start time on, and at the end time; 0 writes the start and "
        "the end only.");
      prm.declare_entry(
        "Progress",
        "auto",
        Selection("auto|on|off"),
        "Progress reports. auto: on a terminal (standard error) a line "
        "rewritten in place; otherwise (a batch job) a line every Progress "
        "interval on standard output. on: the line rewritten in place. "
        "off: none. Unless off, the periodic lines also go to log.txt in "
        "the output directory, with a last line saying how the run ended.");
      prm.declare_entry(
        "Progress interval",
        "10",
        Double(0.1, max),
        "Wall-clock seconds between two lines of the progress log.");
      prm.declare_entry(
        "H1 norm",
        "false",
        Bool(),
        "Accumulate the H1 norm of the trajectory, (integral |q|^2 + "
        "|q'|^2 dt)^(1/2), and report it in summary.json.");
      prm.declare_entry(
        "Field output interval",
        "0",
        Double(0., max),
        "Write the fields of an elastic body (displacement, velocity, J, "
        "strain energy density) for ParaView every this much simulated "
        "time, from the start time on; 0 writes none.");
      prm.declare_entry(
        "Field output format",
        "vtu",
        Selection("vtu|hdf5"),
        "vtu: fields/solution-NNNNN.vtu and the time series solution.pvd; "
        "hdf5: fields/solution-NNNNN.h5 and solution.xdmf.");
    }
    prm.leave_subsection();
  }



  void
  RunParameters::parse_parameters(dealii::ParameterHandler &prm)
  {
    output_directory = prm.get("Output directory");
    if (output_directory.empty())
      throw std::runtime_error("Output directory: must not be empty.");

    prm.enter_subsection("Time integration");
    method         = prm.get("Method");
    start_time     = prm.get_double("Start time");
    end_time       = prm.get_double("End time");
    energy_step    = prm.get_double("Energy step");
    terrace_offset = prm.get_double("Terrace offset");
    time_step      = prm.get_double("Time step");
    blowup_factor  = prm.get_double("Blow-up factor");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    history_interval      = prm.get_double("History interval");
    progress              = prm.get("Progress");
    progress_interval     = prm.get_double("Progress interval");
    h1_norm               = prm.get_bool("H1 norm");
    field_output_interval = prm.get_double("Field output interval");
    field_output_format   = prm.get("Field output format");
    prm.leave_subsection();

    if (!(end_time > start_time))
      throw std::runtime_error(
        "Time integration/End time: must be larger than the start time (" +
        std::to_string(start_time) + ").");
    // Times are resolved to about a million units of round-off of the
    // largest time of the run: a shorter span or output interval could not
    // be stepped through in floating point.
    const double time_resolution =
      std::ldexp(std::numeric_limits<double>::epsilon() *
                   std::max(std::abs(start_time), std::abs(end_time)),
                 20);
    if (end_time - start_time < time_resolution)
      throw std::runtime_error(
        "Time integration/End time: the time span " +
        std::to_string(end_time - start_time) +
        " is below the resolution of floating-point times this far from 0 (" +
        std::to_string(time_resolution) + "); shift the start time to 0.");
    const auto check_interval = [&](const char  *entry,
                                    const double interval,
                                    const double max_outputs) {
      if (interval > 0. && interval < time_resolution)
        throw std::runtime_error(std::string("Output/") + entry +
                                 ": below the resolution of the run's times (" +
                                 std::to_string(time_resolution) + ").");
      if (interval > 0. && (end_time - start_time) / interval > max_outputs)
        throw std::runtime_error(
          std::string("Output/") + entry + ": would write more than " +
          std::to_string(static_cast<long long>(max_outputs)) +
          " outputs over the run; choose a larger interval.");
    };
    check_interval("History interval", history_interval, 1e8);
    check_interval("Field output interval", field_output_interval, 1e5);
    if (method == "energy stepping" && !(energy_step > 0.))
      throw std::runtime_error(
        "Time integration/Energy step: must be positive.");
    if (!(terrace_offset < 1.))
      throw std::runtime_error(
        "Time integration/Terrace offset: must be smaller than 1.");
    if (method != "energy stepping" && !(time_step > 0.))
      throw std::runtime_error("Time integration/Time step: must be positive.");
  }
} // namespace estep
