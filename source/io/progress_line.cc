#include <estep/io/progress_line.h>

#include <unistd.h>

#include <cstdio>

namespace estep
{
  ProgressLine::ProgressLine(const double start_time, const double end_time)
    : start_time(start_time)
    , end_time(end_time)
    , first_time(start_time)
    , wall_start(std::chrono::steady_clock::now())
    , last_print(wall_start)
  {}

  ProgressLine::~ProgressLine()
  {
    if (printed)
      std::fprintf(stderr, "\r\033[K");
  }

  void
  ProgressLine::watch_from(const double t, const std::uint64_t steps)
  {
    first_time = t;
    first_step = steps;
    wall_start = last_print = std::chrono::steady_clock::now();
  }

  bool
  ProgressLine::stderr_is_terminal()
  {
    return isatty(fileno(stderr)) != 0;
  }

  void
  ProgressLine::after_step(const TimeIntegrator &integrator)
  {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_print < std::chrono::milliseconds(250))
      return;
    last_print        = now;
    printed           = true;
    const double wall = std::chrono::duration<double>(now - wall_start).count();
    const double done =
      (integrator.time() - start_time) / (end_time - start_time);
    const double since = integrator.time() - first_time;
    const double left =
      since > 0. ? wall * (end_time - integrator.time()) / since : 0.;
    std::fprintf(stderr,
                 "\r\033[K  t = %-12.6g %5.1f%%  %10.0f steps/s  %6.0f s left",
                 integrator.time(),
                 100. * done,
                 (integrator.n_steps() - first_step) / (wall > 0. ? wall : 1.),
                 left);
    std::fflush(stderr);
  }
} // namespace estep
