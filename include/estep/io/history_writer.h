#ifndef estep_io_history_writer_h
#define estep_io_history_writer_h

#include <estep/io/postprocessor.h>

#include <fstream>
#include <string>

namespace estep
{
  /**
   * Writes history.csv: one row per output time with the time, the energies
   * (kinetic, potential, terraced potential, total T + V and terraced total T +
   * L h), the linear and angular momentum about the origin, the step statistics
   * so far, the smallest and largest step since the previous row (the steps
   * ending after it up to the first one reaching the row's time; the step in
   * progress if none ended), and the system's own observables. Rows are flushed
   * as they are written, so a run that stops early leaves a valid file; a row
   * that cannot be written (a full disk) throws OutputFailed naming the file.
   */
  class HistoryWriter : public Postprocessor
  {
  public:
    /** The history of @p integrator (initialised) in @p filename. */
    HistoryWriter(const std::string    &filename,
                  const TimeIntegrator &integrator);

    /** Opens the file and writes the header. Throws std::runtime_error if it
     * cannot. */
    void
    start() override;

    /** The file's size and the step extremes since the last row. */
    void
    save_state(StateWriter &out) const override;

    /** Cuts the file back to its size at the checkpoint and appends. */
    void
    resume(StateReader &in) override;

    void
    observe(const Snapshot &snapshot) override;

    void
    after_step(const TimeIntegrator &integrator) override;

  private:
    const TimeIntegrator &integrator;
    const std::string     filename;
    const double          start_time;
    std::ofstream         out;
    /** The file's size after the last row. */
    std::uint64_t bytes_written = 0;
    /** Extreme steps since the last row; min > max when none ended since. */
    double smallest_step_since_row, largest_step_since_row;
  };
} // namespace estep

#endif
