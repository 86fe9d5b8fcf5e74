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
   * The parameters of a run that do not belong to a particular system: where
   * output goes, the time integrator and what is written.
   */
  struct RunParameters
  {
    /** Declare the top-level entries and the subsections "Time integration" and
     * "Output". */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Read the entries and check them against each other; throws
     * std::runtime_error. */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    std::string output_directory;

    std::string method;
    double      start_time;
    double      end_time;
    double      energy_step;
    double      terrace_offset;
    double      time_step;
    double      blowup_factor;

    double      history_interval;
    std::string progress;
    double      progress_interval;
    bool        h1_norm;
    double      field_output_interval;
    std::string field_output_format;
  };
} // namespace estep

#endif
