#include <estep/time_integration/time_loop.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <sstream>

namespace estep
{
  void
  RunObserver::observe(const Snapshot &)
  {}

  void
  RunObserver::after_step(const TimeIntegrator &)
  {}

  std::string
  to_string(const RunStatus status)
  {
    switch (status)
      {
        case RunStatus::completed:
          return "completed";
        case RunStatus::unstable:
          return "unstable";
        case RunStatus::stalled:
          return "stalled";
        case RunStatus::failed:
          return "failed";
        case RunStatus::interrupted:
          return "interrupted";
      }
    return "unknown";
  }



  namespace
  {
    /** Set by request_interruption(), read by the time loop. */
    volatile std::sig_atomic_t interruption = 0;

    /** Steps in a row that leave the time where it is before the run is
     * declared stalled (events at one instant are legitimate, a few). */
    constexpr unsigned int max_steps_in_place = 10000;
  } // namespace



  void
  request_interruption(const int signal) noexcept
  {
    interruption = signal;
  }



  TimeLoopResult
  run_time_loop(TimeIntegrator                   &integrator,
                const TimeLoopSettings           &settings,
                const std::vector<RunObserver *> &observers)
  {
    const auto              wall_start = std::chrono::steady_clock::now();
    const MechanicalSystem &system     = integrator.mechanical_system();
    TimeLoopResult          result;

    const double t0    = settings.start_time;
    const double t_end = settings.end_time;
    const double T0    = kinetic_energy(system, integrator.velocity());
    const double V0    = system.energy(integrator.position());
    const double bound = settings.blowup_factor * (std::abs(T0) + std::abs(V0));
    unsigned int n_out = 0;
    const auto   output_at = [&](const unsigned int k) {
      const double t_k = t0 + k * settings.output_interval;
      return (settings.output_interval > 0. && t_k < t_end) ? t_k : t_end;
    };

    const auto emit_outputs_until = [&](const double t_reached) {
      // Output times in (previous, t_reached], the end time last.
      while (n_out != static_cast<unsigned int>(-1))
        {
          const double t_k = output_at(n_out);
          if (t_k > t_reached)
            break;
          const Snapshot snapshot = integrator.dense_output(t_k);
          for (RunObserver *observer : observers)
            observer->observe(snapshot);
          n_out = (t_k == t_end) ? static_cast<unsigned int>(-1) : n_out + 1;
        }
    };

    emit_outputs_until(t0);
    try
      {
        unsigned int n_steps_in_place = 0;
        while (integrator.time() < t_end)
          {
            const double t_before = integrator.time();
            integrator.step(t_end);
            n_steps_in_place =
              (integrator.time() > t_before) ? 0 : n_steps_in_place + 1;
            if (n_steps_in_place == max_steps_in_place)
              {
                std::ostringstream message;
                message << "The run stalled at t = " << integrator.time()
                        << ": " << max_steps_in_place
                        << " steps in a row did not advance the time.";
                throw StalledRun(message.str());
              }
            const double T = kinetic_energy(system, integrator.velocity());
            if (!std::isfinite(T) || (bound > 0. && T > bound))
              {
                std::ostringstream message;
                message << "The run became unstable at t = "
                        << integrator.time() << ": the kinetic energy " << T
                        << " exceeds " << settings.blowup_factor
                        << " times the initial energy scale (Blow-up factor).";
                throw UnstableRun(message.str());
              }
            for (RunObserver *observer : observers)
              observer->after_step(integrator);
            emit_outputs_until(integrator.time());
            if (interruption != 0)
              {
                result.status = RunStatus::interrupted;
                result.signal = interruption;
                std::ostringstream message;
                message << "Interrupted by signal " << result.signal
                        << " at t = " << integrator.time() << ".";
                result.message = message.str();
                break;
              }
          }
      }
    catch (const UnstableRun &unstable)
      {
        result.status  = RunStatus::unstable;
        result.message = unstable.what();
      }
    catch (const StalledRun &stalled)
      {
        result.status  = RunStatus::stalled;
        result.message = stalled.what();
      }
    catch (const OutputFailed &failure)
      {
        result.status  = RunStatus::failed;
        result.message = failure.what();
      }
    result.final_time   = integrator.time();
    result.wall_seconds = std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - wall_start)
                            .count();
    return result;
  }
} // namespace estep
