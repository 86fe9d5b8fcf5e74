#include <deal.II/base/parameter_handler.h>

#include <estep/app/run_parameters.h>
#include <estep/base/exception_text.h>
#include <estep/io/postprocessor.h>
#include <estep/time_integration/integrator_registry.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  void
  RunParameters::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    const double max = Double::max_double_value;

    prm.declare_entry(
      "Output directory",
      "output",
      dealii::Patterns::DirectoryName(),
      "Directory the run writes to (created if needed): parameters.prm, "
      "history.csv, step_histogram.csv and summary.json.");

    prm.declare_entry(
      "Additional shared libraries",
      "",
      dealii::Patterns::List(dealii::Patterns::FileName()),
      "Shared libraries with your own plugins (problems, materials, time "
      "integrators, postprocessors), separated by commas. estep loads them "
      "before it reads the rest of the input, so that their plugins can be "
      "chosen by name in the same file; a name without '/' is searched as "
      "the dynamic loader searches (LD_LIBRARY_PATH), so give a path such "
      "as ./libmy_plugin.so.");

    prm.declare_entry(
      "Threads",
      "0",
      dealii::Patterns::Integer(0, 4096),
      "Threads the loops over cells use (in each MPI process): 0 for one "
      "per core (under MPI the cores of a machine divided by its "
      "processes), 1 for none; DEAL_II_NUM_THREADS, if set, caps any "
      "number. The "
      "trajectory is the same to the last bit on any number of threads and "
      "processes (the command line's --threads N sets this entry).");

    prm.enter_subsection("Time integration");
    {
      prm.declare_entry("Start time", "0", Double(-max, max), "Initial time.");
      prm.declare_entry("End time",
                        "1",
                        Double(-max, max),
                        "Final time; must exceed the start time.");
      prm.declare_entry(
        "Blow-up factor",
        "1e3",
        Double(1., max),
        "A run stops with status unstable when its kinetic energy exceeds "
        "this factor times the initial |T| + |V|.");
      prm.declare_entry(
        "Energy drift warning",
        "0.1",
        Double(0., max),
        "A run ends with a warning (on standard error and in summary.json) "
        "when the energy its integrator conserves, T + V (T + L h for "
        "energy stepping), differs at an output time (Output/History "
        "interval) from its initial value by more than this fraction of the "
        "initial |T| + |V|: it has not conserved energy and its results say "
        "little.");
      declare_integrator_parameters(prm);
    }
    prm.leave_subsection();

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
        "Checkpoint interval",
        "0",
        Double(0., max),
        "Write the whole state of the run to checkpoint.bin in the output "
        "directory after the first step past every multiple of this much "
        "simulated time (0: not by simulated time). `estep file.prm "
        "--resume` continues from the last checkpoint, bit for bit as if "
        "the run had not stopped (energy stepping, explicit Newmark, energy "
        "momentum; the SUNDIALS methods restart their solvers at the "
        "checkpoint's state and continue within their tolerance). A "
        "checkpoint is also written at the end of "
        "the run and when SIGINT or SIGTERM stops it, whenever either "
        "interval is set.");
      prm.declare_entry(
        "Checkpoint wall interval",
        "15",
        Double(0., max),
        "Also write a checkpoint after every this many minutes of wall time "
        "(0: not by wall time).");
    }
    prm.leave_subsection();

    prm.enter_subsection("Postprocessors");
    declare_postprocessor_parameters(prm);
    prm.leave_subsection();
  }



  void
  RunParameters::parse_parameters(dealii::ParameterHandler &prm)
  {
    output_directory = prm.get("Output directory");
    threads          = prm.get_integer("Threads");
    if (output_directory.empty())
      throw std::runtime_error("Output directory: must not be empty.");

    prm.enter_subsection("Time integration");
    start_time           = prm.get_double("Start time");
    end_time             = prm.get_double("End time");
    blowup_factor        = prm.get_double("Blow-up factor");
    energy_drift_warning = prm.get_double("Energy drift warning");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    history_interval        = prm.get_double("History interval");
    checkpoint_interval     = prm.get_double("Checkpoint interval");
    checkpoint_wall_seconds = 60. * prm.get_double("Checkpoint wall interval");
    prm.leave_subsection();

    if (!(end_time > start_time))
      throw std::runtime_error(
        "Time integration/End time: must be larger than the start time (" +
        message_number(start_time) + ").");
    const double time_resolution = estep::time_resolution(start_time, end_time);
    if (end_time - start_time < time_resolution)
      throw std::runtime_error(
        "Time integration/End time: the time span " +
        message_number(end_time - start_time) +
        " is below the resolution of floating-point times this far from 0 (" +
        message_number(time_resolution) + "); shift the start time to 0.");
    const auto check_interval = [&](const char  *entry,
                                    const double interval,
                                    const double max_outputs) {
      if (interval > 0. && interval < time_resolution)
        throw std::runtime_error(std::string("Output/") + entry +
                                 ": below the resolution of the run's times (" +
                                 message_number(time_resolution) + ").");
      if (interval > 0. && (end_time - start_time) / interval > max_outputs)
        throw std::runtime_error(
          std::string("Output/") + entry + ": would write more than " +
          std::to_string(static_cast<long long>(max_outputs)) +
          " outputs over the run; choose a larger interval.");
    };
    check_interval("History interval", history_interval, 1e8);
    check_interval("Checkpoint interval", checkpoint_interval, 1e6);
  }
} // namespace estep
