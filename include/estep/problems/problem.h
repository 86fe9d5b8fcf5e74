#ifndef estep_problems_problem_h
#define estep_problems_problem_h

#include <estep/base/json_writer.h>
#include <estep/base/plugin_registry.h>
#include <estep/systems/mechanical_system.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace estep
{
  class ElasticBody;

  /**
   * A mechanical system with its initial state, as a parameter file describes
   * it: what a problem plugin creates.
   */
  struct Problem
  {
    /** The name it was chosen by (Problem/System), which the summary and the
     * terminal give; set by create_problem(). */
    std::string                       name;
    std::unique_ptr<MechanicalSystem> system;
    Vector                            q0, v0;
    /** What the summary should say about the problem (units, counts, ...). */
    JsonObject description;
    /** A checksum (estep/base/checksum.h) of what the parameters made of the
     * files they name that q0 and v0 do not show (e.g. vertices held by
     * supports, obstacle surfaces, connectivity); 0 for none. A checkpoint
     * keeps it with q0's and v0's: a resume on changed files is refused. */
    std::uint64_t geometry_checksum = 0;
    /** Warnings about the input, one sentence each: settings the problem
     * does not read (entries_unread_by_type()), a tracked point far from its
     * body (tracked_point_warning()). */
    std::vector<std::string> warnings;
  };

  /**
   * The create function of a problem plugin: reads the problem's parameters
   * (declared by its declare_parameters at the top level of the file) and
   * builds the system and its initial state. Throws std::runtime_error naming
   * the entry on bad input.
   */
  using ProblemFactory = Problem(dealii::ParameterHandler &);

  /** The registered problems. */
  PluginRegistry<ProblemFactory> &
  problem_registry();

  /**
   * Declare `Problem/System` (a Selection of the registered problems), the
   * subsection `Material` that problems with elastic bodies read (see
   * declare_material_parameters()), and every registered problem's own
   * parameters.
   */
  void
  declare_problem_parameters(dealii::ParameterHandler &prm);

  /** The entries of an `Initial velocity` subsection that only its `Type`
   * rigid motion or function reads (entries_unread_by_type()). */
  TypeReaders
  initial_velocity_type_readers();

  /**
   * Declare the top-level subsection `Material` (declare_material_parameters())
   * that the problems with one material read: every problem's parameters
   * have it, and a problem that reads it declares it as its own too, so
   * that for the others it must keep its defaults (create_problem()).
   */
  void
  declare_material_subsection(dealii::ParameterHandler &prm);

  /** The warning for `entry` = @p X, a point of @p body to track, if it lies
   * outside the body's bounding box by more than a quarter of the box's
   * largest side: it is likely a mistake (a point in other units, or of
   * another body), and the body's point nearest to it is tracked. ""
   * otherwise. */
  std::string
  tracked_point_warning(const ElasticBody           &body,
                        const std::string           &entry,
                        const std::array<double, 3> &X);

  /** Build the problem chosen in `Problem/System`. Throws if a top-level
   * subsection that only the other problems read is not at its defaults
   * (a setting the chosen problem would ignore). */
  Problem
  create_problem(dealii::ParameterHandler &prm);
} // namespace estep

/**
 * Register a problem: its name (the value of `Problem/System`), a
 * description, the function declaring its parameters and its create function
 * (a ProblemFactory). A problem's source file ends with this.
 */
#define ESTEP_REGISTER_PROBLEM(name, description, declare, create) \
  ESTEP_REGISTER_PLUGIN(                                           \
    ::estep::problem_registry(), name, description, declare, create)

#endif
