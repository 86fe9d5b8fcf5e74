#ifndef estep_io_checkpoint_h
#define estep_io_checkpoint_h

#include <estep/io/postprocessor.h>
#include <estep/time_integration/time_loop.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace estep
{
  /** The name of the checkpoint in a run's output directory. */
  inline const std::string checkpoint_file_name = "checkpoint.bin";

  /**
   * Write the whole state of a run to @p file: the entries of the parameters
   * it runs with (@p parameters, as printed) that fix its trajectory (all but
   * those a resume may change), @p initial_state (a checksum of the
   * problem's initial state and geometry: what the parameters made of the
   * files and libraries they name), the time loop's state, the integrator's and
   * every postprocessor's. The bytes go to a temporary file, which is
   * flushed to the disk and then renamed over @p file: a kill at any instant
   * leaves either the previous checkpoint or this one, whole. Throws
   * OutputFailed naming the file when it cannot be written.
   */
  void
  write_checkpoint(
    const std::string                                 &file,
    const std::string                                 &parameters,
    const std::uint64_t                                initial_state,
    const TimeLoopState                               &loop,
    const TimeIntegrator                              &integrator,
    const std::vector<std::unique_ptr<Postprocessor>> &postprocessors);

  /**
   * A checkpoint read back: verified when read (its format and checksum),
   * then restored into a run built from the same parameters.
   */
  class Checkpoint
  {
  public:
    /** Read and verify @p file; throws std::runtime_error naming it. */
    explicit Checkpoint(const std::string &file);

    /**
     * Throws std::runtime_error naming the first entry in which @p parameters
     * (as printed) differ from the checkpoint's. Only the end time, the
     * checkpoint entries, the threads and the output directory (moved with
     * its checkpoint) may change on a resume.
     */
    void
    check_parameters(const std::string &parameters) const;

    /** Throws std::runtime_error unless @p initial_state is the checkpoint's
     * (a mesh file changed since, for one). */
    void
    check_initial_state(const std::uint64_t initial_state) const;

    /** The checksum of the checkpoint's contents. */
    std::uint64_t
    checksum() const;

    /** Restore the integrator's state; returns the time loop's. */
    TimeLoopState
    restore(TimeIntegrator &integrator) const;

    /** Let the postprocessors resume their outputs (once the output
     * directory is ready): all of them, or, if @p only_those_on_every_rank,
     * those that run on every MPI process (see
     * Postprocessor::runs_on_every_rank()), as the other processes do; in
     * start_order(). */
    void
    resume(const std::vector<std::unique_ptr<Postprocessor>> &postprocessors,
           const bool only_those_on_every_rank = false) const;

  private:
    std::string   file;
    std::uint64_t contents_checksum;
    /** The fixed entries, one "Section/Entry = value" per line. */
    std::string              parameters;
    std::uint64_t            initial_state_checksum;
    std::string              loop_state, integrator_state;
    std::vector<std::string> postprocessor_states;
  };
} // namespace estep

#endif
