#include <estep/time_integration/time_integrator.h>

#include <algorithm>

namespace estep
{
  TimeIntegrator::TimeIntegrator(const MechanicalSystem &system)
    : system(system)
  {}

  void
  TimeIntegrator::count_step()
  {
    const double dt = t - t_previous;
    smallest_step   = (steps == 0) ? dt : std::min(smallest_step, dt);
    largest_step    = (steps == 0) ? dt : std::max(largest_step, dt);
    ++steps;
  }
} // namespace estep
