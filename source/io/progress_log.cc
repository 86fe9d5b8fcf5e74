#include <deal.II/base/parameter_handler.h>

#include <estep/io/progress_log.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace estep
{
  ProgressLog::ProgressLog(const std::string    &filename,
                           const TimeIntegrator &integrator,
                           const double          start_time,
                           const double          end_time,
                           const double          interval,
                           const bool            terminal)
    : filename(filename)
    , integrator(integrator)
    , start_time(start_time)
    , end_time(end_time)
    , interval(interval)
    , to_standard_output(!terminal)
    , line(terminal ? std::make_unique<ProgressLine>(start_time, end_time) :
                      nullptr)
    , wall_start(std::chrono::steady_clock::now())
    , last_line(wall_start)
    , first_time(start_time)
  {}



  void
  ProgressLog::start()
  {
    out.open(filename);
    if (!out)
      throw std::runtime_error("Cannot open the log file <" + filename +
                               "> for writing.");
  }



  void
  ProgressLog::resume(StateReader &)
  {
    out.open(filename, std::ios::app);
    if (!out)
      throw std::runtime_error("Cannot open the log file <" + filename +
                               "> for appending.");
    first_time = integrator.time();
    first_step = integrator.n_steps();
    wall_start = last_line = std::chrono::steady_clock::now();
    if (line)
      line->watch_from(first_time, first_step);
    write(integrator, ", resumed from the checkpoint");
  }



  void
  ProgressLog::after_step(const TimeIntegrator &integrator)
  {
    if (line)
      line->after_step(integrator);
    if (std::chrono::steady_clock::now() - last_line >= interval)
      write(integrator, "");
  }



  void
  ProgressLog::finish(const TimeLoopResult &result)
  {
    line.reset();
    if (result.status == RunStatus::failed)
      return;
    write(integrator, ", " + to_string(result.status));
    // Why a run ended early (unstable, stalled, penetrated, interrupted),
    // as on the terminal.
    if (!result.message.empty())
      out << "estep: " << result.message << std::endl;
    if (!out)
      throw OutputFailed("Writing the log file <" + filename +
                         "> failed (is the disk full?).");
  }



  void
  ProgressLog::write(const TimeIntegrator &integrator,
                     const std::string    &suffix)
  {
    last_line = std::chrono::steady_clock::now();
    const double wall =
      std::chrono::duration<double>(last_line - wall_start).count();
    const double done =
      (integrator.time() - start_time) / (end_time - start_time);
    const double left = integrator.time() > first_time ?
                          wall * (end_time - integrator.time()) /
                            (integrator.time() - first_time) :
                          0.;
    // A line with a suffix closes the log or opens a resumed part: no time
    // left to tell.
    const bool says_left = suffix.empty();
    // Whole seconds (at most 9 digits), or three digits of a time too long
    // to wait for.
    const bool waitable      = left < 1e9;
    char       time_left[64] = "";
    if (says_left)
      std::snprintf(time_left,
                    sizeof(time_left),
                    ", %.*g s left",
                    waitable ? 9 : 3,
                    waitable ? std::round(left) : left);
    char line[256];
    std::snprintf(line,
                  sizeof(line),
                  "estep: t = %.6g (%.1f%%), %llu steps, %.0f steps/s, %.1f s "
                  "elapsed%s",
                  integrator.time(),
                  100. * done,
                  static_cast<unsigned long long>(integrator.n_steps()),
                  (integrator.n_steps() - first_step) / (wall > 0. ? wall : 1.),
                  wall,
                  time_left);
    if (to_standard_output)
      std::cout << line << suffix << std::endl;
    out << line << suffix << std::endl;
    if (!out)
      throw OutputFailed("Writing the log file <" + filename +
                         "> failed (is the disk full?).");
  }



  namespace
  {
    void
    declare_progress_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Progress");
      prm.declare_entry(
        "Mode",
        "auto",
        dealii::Patterns::Selection("auto|terminal|batch"),
        "terminal: a line on standard error rewritten in place; batch: a "
        "line every Interval on standard output; auto: terminal when "
        "standard error is a terminal, batch otherwise. Either way the "
        "periodic lines go to log.txt in the output directory, then a line "
        "saying how the run ended and, if it ended early, why.");
      prm.declare_entry("Interval",
                        "10",
                        dealii::Patterns::Double(
                          0.1, dealii::Patterns::Double::max_double_value),
                        "Wall-clock seconds between two lines of the log.");
      prm.leave_subsection();
    }

    std::unique_ptr<Postprocessor>
    create_progress(dealii::ParameterHandler   &prm,
                    const PostprocessorContext &run)
    {
      prm.enter_subsection("Progress");
      const std::string mode     = prm.get("Mode");
      const double      interval = prm.get_double("Interval");
      prm.leave_subsection();
      return std::make_unique<ProgressLog>(
        (std::filesystem::path(run.output_directory) / "log.txt").string(),
        run.integrator,
        run.start_time,
        run.end_time,
        interval,
        mode == "terminal" ||
          (mode == "auto" && ProgressLine::stderr_is_terminal()));
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "progress",
  "progress lines (simulated time, steps per second, time left) on the "
  "terminal or, in a batch job, on standard output, and in log.txt "
  "(subsection Progress).",
  estep::declare_progress_parameters,
  estep::create_progress)
