#ifndef estep_app_problem_h
#define estep_app_problem_h

#include <estep/io/json_writer.h>
#include <estep/systems/mechanical_system.h>

#include <memory>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /**
   * A mechanical system with its initial state, as a parameter file describes
   * it.
   */
  struct Problem
  {
    std::unique_ptr<MechanicalSystem> system;
    Vector                            q0, v0;
    /** What the summary should say about the problem (units, counts, ...). */
    JsonObject description;
  };

  /**
   * Declare the subsection "Problem" (which system to build) and the parameters
   * of every system estep can build.
   */
  void
  declare_problem_parameters(dealii::ParameterHandler &prm);

  /**
   * Build the system chosen in "Problem/System" and its initial state. Throws
   * std::runtime_error with a clear message on inconsistent input.
   */
  Problem
  create_problem(dealii::ParameterHandler &prm);
} // namespace estep

#endif
