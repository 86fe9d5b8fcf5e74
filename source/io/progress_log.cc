#include <estep/io/progress_log.h>

#include <cstdio>
#include <iostream>

namespace estep
{
  ProgressLog::ProgressLog(const std::string &filename,
                           const double       start_time,
                           const double       end_time,
                           const double       interval,
                           const bool         to_standard_output)
    : filename(filename)
    , start_time(start_time)
    , end_time(end_time)
    , interval(interval)
    , to_standard_output(to_standard_output)
    , out(filename)
    , wall_start(std::chrono::steady_clock::now())
    , last_line(wall_start)
  {
    if (!out)
      throw std::runtime_error("Cannot open the log file <" + filename +
                               "> for writing.");
  }



  void
  ProgressLog::after_step(const TimeIntegrator &integrator)
  {
    if (std::chrono::steady_clock::now() - last_line >= interval)
      write(integrator, "");
  }



  void
  ProgressLog::finish(const TimeIntegrator &integrator,
                      const std::string    &status)
  {
    write(integrator, ", " + status);
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
    char line[256];
    std::snprintf(line,
                  sizeof(line),
                  "estep: t = %.6g (%.1f%%), %llu steps, %.0f steps/s, "
                  "%.1f s elapsed, %.0f s left",
                  integrator.time(),
                  100. * done,
                  static_cast<unsigned long long>(integrator.n_steps()),
                  integrator.n_steps() / (wall > 0. ? wall : 1.),
                  wall,
                  done > 0. ? wall * (1. - done) / done : 0.);
    if (to_standard_output)
      std::cout << line << suffix << std::endl;
    out << line << suffix << std::endl;
    if (!out)
      throw OutputFailed("Writing the log file <" + filename +
                         "> failed (is the disk full?).");
  }
} // namespace estep
