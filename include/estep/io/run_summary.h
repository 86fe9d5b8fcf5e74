#ifndef estep_io_run_summary_h
#define estep_io_run_summary_h

#include <estep/base/json_writer.h>
#include <estep/io/postprocessor.h>
#include <estep/problems/problem.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace estep
{
  /** The parts of a run that its summary describes. */
  struct RunRecord
  {
    const Problem                                     &problem;
    const TimeIntegrator                              &integrator;
    const std::vector<std::unique_ptr<Postprocessor>> &postprocessors;
    double                                             start_time, end_time;
    /** Warnings about the input (each a sentence): settings the run
     * ignores, a tracked point far from its body, more threads than cores. */
    const std::vector<std::string> &input_warnings;
    /** The time of the checkpoint a resumed run took over from; none for a
     * run from the start. */
    std::optional<double> resumed_from_time;
  };

  /**
   * The short summary of a run that has not run to an end: estep's version,
   * @p status ("running", or "failed" when its outputs could not be opened),
   * @p message, the system, the method, the time span and, for a resumed
   * run, the time it resumed from.
   */
  JsonObject
  status_summary(const RunRecord   &run,
                 const std::string &status,
                 const std::string &message);

  /**
   * The summary of a run that ended as @p result says: status_summary(), the
   * warnings (the integrator's at the start, the time loop's at the end, the
   * ignored settings),
   * the problem's description, the counts of work and steps, the energies
   * and momenta at the start and the end with their drifts (and the largest
   * drift of the conserved energy over the output times), the integrator's
   * own figures and every postprocessor's.
   */
  JsonObject
  run_summary(const RunRecord &run, const TimeLoopResult &result);
} // namespace estep

#endif
