#include <estep/base/distributed_blocks.h>
#include <estep/base/interruption.h>
#include <estep/time_integration/time_loop.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace estep
{
  void
  RunObserver::observe(const Snapshot &)
  {}

  void
  RunObserver::after_step(const TimeIntegrator &)
  {}

  double
  time_resolution(const double start_time, const double end_time)
  {
    return std::ldexp(std::numeric_limits<double>::epsilon() *
                        std::max(std::abs(start_time), std::abs(end_time)),
                      20);
  }



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
        case RunStatus::penetrated:
          return "penetrated";
      }
    return "unknown";
  }



  namespace
  {
    /** Steps in a row that leave the time where it is before the run is
     * declared stalled (events at one instant are legitimate, a few). */
    constexpr unsigned int max_steps_in_place = 10000;

    /** Thrown when bodies have passed into each other; the run ends with
     * status penetrated. */
    class PenetratedRun : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    /**
     * Throws std::logic_error, naming the integrator, if its last step broke
     * what every TimeIntegrator must do (an integrator of a user's own may):
     * step from @p t_before to at most @p t_limit, and count the step.
     */
    void
    check_step_rules(const TimeIntegrator &integrator,
                     const double          t_before,
                     const std::uint64_t   steps_before,
                     const double          t_limit)
    {
      std::ostringstream message;
      if (integrator.time() > t_limit)
        message << "stepped from t = " << t_before << " to "
                << integrator.time() << ", past the limit " << t_limit
                << " it was given";
      else if (integrator.time() > t_before &&
               integrator.n_steps() == steps_before)
        message << "stepped from t = " << t_before << " to "
                << integrator.time() << " without counting the step "
                << "(count_step())";
      else
        return;
      throw std::logic_error(
        "Time integration/Method = " + integrator.name() + " " + message.str() +
        ": a time integrator must not (doc/extending.md).");
    }

    /** The message of a run that an unexpected exception ended at @p t. */
    std::string
    failure_message(const double t, const std::string &what)
    {
      std::ostringstream message;
      message << "The run failed at t = " << t << ": " << what;
      return message.str();
    }
  } // namespace



  void
  TimeLoopState::save(StateWriter &out) const
  {
    out.put(blowup_bound);
    out.put(steps_in_place);
    out.put(energy_scale);
    out.put(initial_energy);
    out.put(largest_energy_drift);
    out.put(largest_energy_drift_time);
    out.put(outputs_passed);
  }



  void
  TimeLoopState::load(StateReader &in)
  {
    blowup_bound              = in.get<double>();
    steps_in_place            = in.get<std::uint64_t>();
    energy_scale              = in.get<double>();
    initial_energy            = in.get<double>();
    largest_energy_drift      = in.get<double>();
    largest_energy_drift_time = in.get<double>();
    outputs_passed            = in.get<std::uint64_t>();
  }



  namespace
  {
    /**
     * The times t_k = t0 + k interval below t_end, then t_end (an interval
     * of 0: t0 and t_end): output times and checkpoint times. next() is the
     * first one after the time reached.
     */
    class TimeGrid
    {
    public:
      TimeGrid(const double t0, const double t_end, const double interval)
        : t0(t0)
        , t_end(t_end)
        , interval(interval)
      {}

      /** The grid's k-th time. */
      double
      at(const std::uint64_t k) const
      {
        if (!(interval > 0.))
          return k == 0 ? t0 : t_end;
        const double t_k = t0 + static_cast<double>(k) * interval;
        return t_k < t_end ? t_k : t_end;
      }

      /** Whether every time of the grid has been passed. */
      bool
      done() const
      {
        return finished;
      }

      /** The first time not passed yet. */
      double
      next() const
      {
        return at(k);
      }

      /** Pass the next time. */
      void
      advance()
      {
        finished = (at(k) == t_end);
        ++k;
      }

      /** How many times have been passed. */
      std::uint64_t
      passed() const
      {
        return k;
      }

      /**
       * Take over at time @p t after a run that passed the first @p n times
       * of its grid (a resumed run, whose end time may be later). If the
       * last of them lies after t, the run ended at t with a row there that
       * stood in for it: that time is visited again, unless the two differ
       * only by round-off (an end time 0.3 for the time 3 x 0.1).
       */
      void
      resume_after(const std::uint64_t n, const double t)
      {
        k = n;
        if (n > 0 && interval > 0.)
          {
            const double stood_for = t0 + static_cast<double>(n - 1) * interval;
            if (stood_for - t > 1e-12 * std::max(std::abs(t), interval))
              k = n - 1;
          }
        finished = k > 0 && at(k - 1) == t_end && t_end <= t;
      }

      /** Pass every time up to and including @p t, without visiting them. */
      void
      skip_to(const double t)
      {
        k = 0;
        if (interval > 0. && t > t0)
          {
            const double estimate = std::floor((t - t0) / interval) - 1.;
            if (estimate > 0. && estimate < 1e18)
              k = static_cast<std::uint64_t>(estimate);
          }
        while (!finished && at(k) <= t)
          advance();
      }

    private:
      const double  t0, t_end, interval;
      std::uint64_t k        = 0;
      bool          finished = false;
    };



    TimeLoopResult
    continue_time_loop(TimeIntegrator                   &integrator,
                       const TimeLoopSettings           &settings,
                       const std::vector<RunObserver *> &observers,
                       TimeLoopState                     state,
                       const bool                        resumed)
    {
      using Clock                        = std::chrono::steady_clock;
      const auto              wall_start = Clock::now();
      const MechanicalSystem &system     = integrator.mechanical_system();
      TimeLoopResult          result;
      const double            t_end = settings.end_time;

      TimeGrid outputs(settings.start_time, t_end, settings.output_interval);
      TimeGrid checkpoints(settings.start_time,
                           t_end,
                           settings.checkpoint_interval);
      if (resumed)
        outputs.resume_after(state.outputs_passed, integrator.time());
      checkpoints.skip_to(integrator.time());
      auto last_checkpoint = wall_start;
      // The integrator's counters at the first step that left the time where
      // it was (a stall's message tells what it did since).
      std::vector<Counter> counters_in_place;

      const auto emit_outputs_until = [&](const double t_reached) {
        // Output times in (previous, t_reached], the end time last.
        while (!outputs.done() && outputs.next() <= t_reached)
          {
            const Snapshot snapshot = integrator.dense_output(outputs.next());
            // An inverted cell, or a state beyond what double precision
            // evaluates (a body flung 1e100 m away, one of 1e-30 m): no row
            // of it is written.
            if (!std::isfinite(snapshot.kinetic_energy) ||
                !std::isfinite(snapshot.potential_energy))
              {
                std::ostringstream message;
                message << "The run became unstable at t = " << snapshot.t
                        << ": the energies T = " << snapshot.kinetic_energy
                        << " and V = " << snapshot.potential_energy
                        << " are not both finite (a cell inverted, or the "
                           "state beyond what double precision evaluates).";
                throw UnstableRun(message.str());
              }
            if (state.energy_scale > 0.)
              {
                const double drift =
                  std::abs(snapshot.kinetic_energy +
                           snapshot.terraced_potential_energy -
                           state.initial_energy) /
                  state.energy_scale;
                if (!(drift <= state.largest_energy_drift))
                  {
                    state.largest_energy_drift      = drift;
                    state.largest_energy_drift_time = snapshot.t;
                  }
              }
            for (RunObserver *observer : observers)
              observer->observe(snapshot);
            outputs.advance();
            state.outputs_passed = outputs.passed();
          }
      };
      const auto write_checkpoint = [&]() {
        integrator.complete_state();
        settings.write_checkpoint(state);
        last_checkpoint = Clock::now();
      };
      const auto end_interrupted = [&](const int          signal,
                                       const std::string &where) {
        result.status = RunStatus::interrupted;
        result.signal = signal;
        std::ostringstream message;
        message << "Interrupted by signal " << signal
                << " at t = " << integrator.time() << where << ".";
        result.message = message.str();
      };
      const auto checkpoint_due = [&]() {
        if (!settings.write_checkpoint)
          return false;
        if (settings.checkpoint_interval > 0. && !checkpoints.done() &&
            checkpoints.next() <= integrator.time())
          {
            checkpoints.skip_to(integrator.time());
            return true;
          }
        if (!(settings.checkpoint_wall_seconds > 0.))
          return false;
        // The first rank's clock decides, for every rank (a checkpoint
        // completes the state, which the ranks do together).
        char due = std::chrono::duration<double>(Clock::now() - last_checkpoint)
                     .count() >= settings.checkpoint_wall_seconds;
        broadcast_from_first_rank(&due, 1);
        return due != 0;
      };

      try
        {
          if (!resumed)
            emit_outputs_until(settings.start_time);
          while (integrator.time() < t_end)
            {
              const double        t_before     = integrator.time();
              const std::uint64_t steps_before = integrator.n_steps();
              try
                {
                  integrator.step(t_end);
                }
              catch (const StepInterrupted &abandoned)
                {
                  end_interrupted(abandoned.signal,
                                  " (in the middle of a step, "
                                  "which was abandoned)");
                  break;
                }
              check_step_rules(integrator, t_before, steps_before, t_end);
              state.steps_in_place =
                (integrator.time() > t_before) ? 0 : state.steps_in_place + 1;
              if (state.steps_in_place == 1)
                counters_in_place = integrator.counters();
              if (state.steps_in_place == max_steps_in_place)
                {
                  std::ostringstream message;
                  message << "The run stalled at t = " << integrator.time()
                          << ": " << max_steps_in_place
                          << " steps in a row did not advance the time";
                  // What the integrator did meanwhile, e.g. reflections.
                  const std::vector<Counter> now = integrator.counters();
                  if (now.size() == counters_in_place.size())
                    {
                      message << " (" << integrator.name() << ", the last "
                              << max_steps_in_place - 1 << " of them:";
                      for (std::size_t i = 0; i < now.size(); ++i)
                        if (now[i].second != counters_in_place[i].second)
                          message
                            << ' ' << now[i].first << " +"
                            << now[i].second - counters_in_place[i].second;
                      message << ')';
                    }
                  message << '.';
                  throw StalledRun(message.str());
                }
              const double T = integrator.current_kinetic_energy();
              if (!std::isfinite(T) ||
                  (state.blowup_bound > 0. && T > state.blowup_bound))
                {
                  std::ostringstream message;
                  message
                    << "The run became unstable at t = " << integrator.time()
                    << ": the kinetic energy " << T << " exceeds "
                    << settings.blowup_factor
                    << " times the initial energy scale (Blow-up factor).";
                  throw UnstableRun(message.str());
                }
              if (const std::string penetration =
                    system.penetration(integrator.position());
                  !penetration.empty())
                {
                  std::ostringstream message;
                  message << "A body passed through contact at t = "
                          << integrator.time() << ": " << penetration;
                  throw PenetratedRun(message.str());
                }
              for (RunObserver *observer : observers)
                observer->after_step(integrator);
              emit_outputs_until(integrator.time());
              // On several MPI ranks, a signal that reached one of them ends
              // the run on all, after the same step.
              if (const int signal = requested_interruption(); signal != 0)
                {
                  end_interrupted(signal, "");
                  break;
                }
              if (integrator.time() < t_end && checkpoint_due())
                write_checkpoint();
            }
          if (settings.write_checkpoint)
            write_checkpoint();
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
      catch (const PenetratedRun &penetrated)
        {
          result.status  = RunStatus::penetrated;
          result.message = penetrated.what();
        }
      catch (const OutputFailed &failure)
        {
          result.status  = RunStatus::failed;
          result.message = failure.what();
        }
      // Anything else, e.g. a plugin's integrator or postprocessor that
      // throws: the run failed, and its summary says so.
      catch (const std::exception &error)
        {
          result.status  = RunStatus::failed;
          result.message = failure_message(integrator.time(), error.what());
        }
      catch (...)
        {
          result.status  = RunStatus::failed;
          result.message = failure_message(integrator.time(),
                                           "an exception of an unknown type");
        }
      // Every rank ends a run in the same state, unless it failed: an
      // output of the first rank fails on it alone.
      if (result.status != RunStatus::failed)
        integrator.complete_state();
      result.largest_energy_drift      = state.largest_energy_drift;
      result.largest_energy_drift_time = state.largest_energy_drift_time;
      if (result.status != RunStatus::unstable &&
          !(state.largest_energy_drift <= settings.energy_drift_warning))
        {
          std::ostringstream message;
          message << "Time integration/Energy drift warning: the energy "
                  << integrator.conserved_energy()
                  << " drifted from its initial value by "
                  << state.largest_energy_drift
                  << " times the initial energy scale |T| + |V| = "
                  << state.energy_scale
                  << " (at t = " << state.largest_energy_drift_time
                  << "), more than the " << settings.energy_drift_warning
                  << " allowed: the run has not conserved energy and its "
                     "results say little; take a smaller step (an adaptive "
                     "method: tighter tolerances).";
          result.warnings.push_back(message.str());
        }
      result.final_time   = integrator.time();
      result.wall_seconds = std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - wall_start)
                              .count();
      return result;
    }
  } // namespace



  TimeLoopResult
  run_time_loop(TimeIntegrator                   &integrator,
                const TimeLoopSettings           &settings,
                const std::vector<RunObserver *> &observers)
  {
    const MechanicalSystem &system = integrator.mechanical_system();
    TimeLoopState           state;
    const double            T0 = kinetic_energy(system, integrator.velocity());
    const double            V0 = system.energy(integrator.position());
    state.energy_scale         = std::abs(T0) + std::abs(V0);
    state.blowup_bound         = settings.blowup_factor * state.energy_scale;
    const Snapshot start       = integrator.dense_output(integrator.time());
    state.initial_energy =
      start.kinetic_energy + start.terraced_potential_energy;
    return continue_time_loop(integrator, settings, observers, state, false);
  }



  TimeLoopResult
  resume_time_loop(TimeIntegrator                   &integrator,
                   const TimeLoopSettings           &settings,
                   const std::vector<RunObserver *> &observers,
                   const TimeLoopState              &state)
  {
    return continue_time_loop(integrator, settings, observers, state, true);
  }
} // namespace estep
