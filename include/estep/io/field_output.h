#ifndef estep_io_field_output_h
#define estep_io_field_output_h

#include <estep/io/postprocessor.h>

#include <memory>
#include <string>
#include <vector>

namespace estep
{
  class ElasticBodies;

  /**
   * Field output of elastic bodies for ParaView, every @p interval of
   * simulated time from the start time on, and at the end time (the exact
   * dense output of the integrator): the displacement and the velocity (vertex
   * fields), the volume ratio J, the strain energy density, the Cauchy stress
   * tensor and the von Mises stress (cell fields).
   *
   * Format "vtu": one fields/solution-NNNNN.vtu per snapshot (VtuFile: the
   * mesh's own vertices and cells, compressed), or for several bodies one
   * fields/solution-NNNNN-B.vtu per body B = 1, 2, ... joined by the
   * multiblock file fields/solution-NNNNN.vtm; and the time series
   * solution.pvd. The series is rewritten atomically after a snapshot if the
   * last rewrite is a second old or more, and by finish(): it is valid while
   * the run goes on, lists only complete files and lags at most a second
   * behind them (rewriting it after every snapshot cost seconds on a slow
   * disk, which ext4 makes flush a file renamed over another). On several MPI
   * processes each writes its piece of a body, the cells of its blocks
   * (solution-NNNNN-pR.vtu for process R), and the first the
   * solution-NNNNN.pvtu that joins them, which the series lists.
   *
   * Format "hdf5": the bodies' points and cells (and the obstacles'
   * triangles) once in fields/mesh.h5, each snapshot's fields in
   * fields/solution-NNNNN.h5, a group per body (body1, body2, ...) with the
   * same fields as in vtu, stored as doubles, the cell fields per cell; and
   * the time series solution.xdmf. On several MPI processes every process
   * writes its rows into the same files (its cells, a share of the points):
   * their datasets are those of one process, to the last bit.
   */
  class FieldOutput : public Postprocessor
  {
  public:
    enum class Format
    {
      vtu,
      hdf5
    };

    FieldOutput(const ElasticBodies &bodies,
                const std::string   &directory,
                const Format         format,
                const double         start_time,
                const double         interval,
                const double         end_time);

    ~FieldOutput() override;

    /** Creates the folder fields/, and writes the obstacles (vtu) or the
     * meshes (hdf5). */
    void
    start() override;

    /** The next snapshot time and the series written so far. */
    void
    save_state(StateWriter &out) const override;

    /** Starts again, with the series of the checkpoint (which must be of
     * the same format). */
    void
    resume(StateReader &in) override;

    /** Writes the snapshots due in (previous_time(), time()], and the start. */
    void
    after_step(const TimeIntegrator &integrator) override;

    /** Brings the time series file up to date (unless the run failed: its
     * disk may not take it). */
    void
    finish(const TimeLoopResult &result) override;

    /** Every MPI process writes its piece of each body. */
    bool
    runs_on_every_rank() const override;

    /** Number of snapshots written. */
    unsigned int
    n_snapshots() const;

  private:
    void
    write(const Snapshot &snapshot);

    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace estep

#endif
