#ifndef estep_composite_contact_parameters_h
#define estep_composite_contact_parameters_h

#include <string>

namespace dealii
{
  class ParameterHandler;
} // namespace dealii

namespace estep
{
  /**
   * How the bodies of a ContactSystem interact, as read from the "Contact"
   * subsection of a parameter file.
   */
  struct ContactParameters
  {
    /** The contact model. */
    enum class Mode
    {
      /** No contact: the bodies pass through each other. */
      none,
      /** Penalty energy I = 1/(2 eps) sum |A - B|^2 over intersecting pairs of
       * boundary triangles (a term of V). */
      penalty,
      /** Exact impenetrability: an energy step of infinite height (reflection
       * at the first vertex-face or edge-edge contact along each flight). */
      impenetrability
    };

    /** The contact model. */
    Mode mode = Mode::penalty;
    /** Penalty parameter eps > 0 (units length^2 / energy). */
    double penalty_parameter = 1e-7;
    /** Whether the boundary of a body may contact itself (pairs of triangles
     * that share a vertex are always excluded). */
    bool self_contact = false;
    /** Distance tolerance of the continuous collision detection
     * (impenetrability; absolute length). */
    double ccd_tolerance = 1e-6;

    /**
     * Declare the subsection "Contact" (entries "Mode", "Penalty parameter",
     * "Self contact", "Collision tolerance") in the current subsection of @p
     * prm, with documentation and patterns.
     */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Read the subsection declared by declare_parameters(). A setting that
     * the mode does not use (a penalty parameter without the penalty mode,
     * ...) is an error: nothing is silently ignored. */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    /** Whether every entry has its default value (for a problem without
     * contact, anything else is an error). */
    bool
    is_default() const;

    /** "none", "penalty" or "impenetrability". */
    static std::string
    mode_name(const Mode mode);

    /** The mode called @p name; throws dealii::ExcMessage for another name. */
    static Mode
    parse_mode(const std::string &name);
  };
} // namespace estep

#endif
