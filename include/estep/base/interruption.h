#ifndef estep_base_interruption_h
#define estep_base_interruption_h

#include <stdexcept>

namespace estep
{
  /**
   * Ask the run to stop, reporting @p signal (0 withdraws the request).
   * Async-signal-safe: meant for a signal handler. The time loop stops after
   * the current step; a computation that can take long inside a step (a
   * crawling first-crossing search) polls with abandon_step_if_interrupted().
   */
  void
  request_interruption(const int signal) noexcept;

  /** The signal requested on any MPI rank, 0 if none. Collective. */
  int
  requested_interruption();

  /** Thrown inside a step that was abandoned for a requested interruption;
   * the time loop ends the run as interrupted. */
  class StepInterrupted : public std::runtime_error
  {
  public:
    /** The step was abandoned for @p signal. */
    explicit StepInterrupted(const int signal);

    /** The signal that was requested. */
    const int signal;
  };

  /** Throws StepInterrupted if an interruption was requested on any MPI rank.
   * Collective: every rank must call it at the same point of the same
   * computation. */
  void
  abandon_step_if_interrupted();
} // namespace estep

#endif
