#ifndef estep_io_postprocessor_h
#define estep_io_postprocessor_h

#include <estep/base/binary_state.h>
#include <estep/base/json_writer.h>
#include <estep/base/plugin_registry.h>
#include <estep/time_integration/time_loop.h>

#include <memory>
#include <string>
#include <vector>

namespace estep
{
  /**
   * What a run writes besides its summary: a history, field snapshots, a
   * progress log, contact statistics, ... A postprocessor watches the run (a
   * RunObserver) and goes through four stages: it is created while the input
   * is checked (it may refuse a system it cannot serve, and must not touch the
   * disk yet); start() opens its files once the output directory is ready;
   * the time loop shows it the run; finish() closes it, and add_to_summary()
   * and final_report() say what it found.
   */
  class Postprocessor : public RunObserver
  {
  public:
    /** Open the outputs. Throws std::runtime_error when one cannot be opened
     * (the run then fails). The default does nothing. */
    virtual void
    start();

    /**
     * @name Checkpoints
     * A postprocessor that carries something from step to step (counts,
     * extremes, the list of files written, the size of a file it appends to)
     * stores it in save_state(); a resumed run calls resume() instead of
     * start() with what it stored, to continue its outputs where the
     * checkpoint was taken (e.g. cutting a file back to its size then and
     * appending). The defaults store nothing and call start().
     * @{
     */
    virtual void
    save_state(StateWriter &out) const;

    virtual void
    resume(StateReader &in);
    /** @} */

    /** The run has ended as @p result says: write what is written at the end.
     * The default does nothing. */
    virtual void
    finish(const TimeLoopResult &result);

    /** Add this postprocessor's figures to summary.json. The default adds
     * nothing. */
    virtual void
    add_to_summary(JsonObject &summary) const;

    /**
     * Whether, on several MPI processes, it runs on every one (each writing
     * its own part, as field output writes a piece per process) rather than
     * on the first alone. Such a postprocessor calls what the processes
     * compute together (MechanicalSystem::energy(),
     * TimeIntegrator::dense_output(), and dense_state() unless the
     * integrator overrides it) on every process alike or not at all, and
     * only the first process's state goes into checkpoints. It may make
     * collective calls of its own (HDF5 output writes one file together): those
     * that run on every rank are started, resumed and called in the same order
     * on every process, and start before the others (start_order()). The
     * default: false.
     */
    virtual bool
    runs_on_every_rank() const;

    /** A line for the terminal at the end of the run, or "" (the default). */
    virtual std::string
    final_report() const;
  };

  /** What a postprocessor may know of its run. */
  struct PostprocessorContext
  {
    /** The initialised integrator (and through it the system). */
    const TimeIntegrator &integrator;
    /** The initial state. */
    const Vector &q0, &v0;
    /** Where the run writes (it exists once start() is called). */
    std::string output_directory;
    double      start_time, end_time;
  };

  /**
   * The create function of a postprocessor plugin: reads its parameters
   * (declared by its declare_parameters in the subsection `Postprocessors`,
   * @p prm in that subsection). Throws std::runtime_error naming the entry on
   * bad input or a system it cannot serve; returns nullptr for a system it has
   * nothing to watch in, when its description says so.
   */
  using PostprocessorFactory =
    std::unique_ptr<Postprocessor>(dealii::ParameterHandler &,
                                   const PostprocessorContext &);

  /** The registered postprocessors. */
  PluginRegistry<PostprocessorFactory> &
  postprocessor_registry();

  /**
   * Declare, in the current subsection (`Postprocessors`), `List` and every
   * postprocessor's own parameters.
   */
  void
  declare_postprocessor_parameters(dealii::ParameterHandler &prm);

  /**
   * The order in which @p postprocessors start or resume (indices into it):
   * those that run on every MPI rank first, so that their collective calls
   * meet on every process before an output of the first process alone may
   * fail; each group in the list's order.
   */
  std::vector<std::size_t>
  start_order(
    const std::vector<std::unique_ptr<Postprocessor>> &postprocessors);

  /** Warnings for the subsections of the current one (`Postprocessors`)
   * that only postprocessors missing from `List` read and that the input
   * sets: their settings are ignored. */
  std::vector<std::string>
  ignored_postprocessor_settings(dealii::ParameterHandler &prm);

  /** The postprocessors named in `List`, in its order. */
  std::vector<std::unique_ptr<Postprocessor>>
  create_postprocessors(dealii::ParameterHandler   &prm,
                        const PostprocessorContext &context);
} // namespace estep

/**
 * Register a postprocessor: its name (an item of `Postprocessors/List`), a
 * description, the function declaring its parameters and its create function
 * (a PostprocessorFactory). A postprocessor's source file ends with this.
 */
#define ESTEP_REGISTER_POSTPROCESSOR(name, description, declare, create) \
  ESTEP_REGISTER_PLUGIN(                                                 \
    ::estep::postprocessor_registry(), name, description, declare, create)

#endif
