#ifndef estep_app_run_parameters_h
#define estep_app_run_parameters_h

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /**
   * The parameters of a run that belong to no plugin: where output goes, the
   * time span, when history rows are written.
   */
  struct RunParameters
  {
    /**
     * Declare the top-level entries (output directory, additional shared
     * libraries), the subsections "Time integration" (the time span and the
     * integrators' parameters), "Output" and "Postprocessors".
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Read the entries of the run itself and check them against each other;
     * throws std::runtime_error. */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    std::string output_directory;
    /** Threads of the cell loops (0: one per core). */
    unsigned int threads;
    double       start_time;
    double       end_time;
    double       blowup_factor;
    double       energy_drift_warning;
    double       history_interval;
    /** Checkpoints every this much simulated time (0: none) and every this
     * many seconds of wall time (0: none). */
    double checkpoint_interval;
    double checkpoint_wall_seconds;
  };
} // namespace estep

#endif
