#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <estep/composite/contact_parameters.h>

#include <stdexcept>

namespace estep
{
  void
  ContactParameters::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry(
      "Mode",
      "penalty",
      dealii::Patterns::Selection("none|penalty|impenetrability"),
      "Contact between the boundaries of the bodies: none; penalty (the "
      "energy 1/(2 eps) sum |A - B|^2 over intersecting pairs of boundary "
      "triangles, A and B the ends of their intersection segment, is added "
      "to the potential); impenetrability (exact: the velocities reflect at "
      "the first vertex-face or edge-edge contact, found by conservative "
      "continuous collision detection).");
    prm.declare_entry("Penalty parameter",
                      "1e-7",
                      dealii::Patterns::Double(0.),
                      "The penalty parameter eps > 0 of the penalty mode "
                      "(units: length^2 / energy). Smaller is stiffer.");
    prm.declare_entry("Self contact",
                      "false",
                      dealii::Patterns::Bool(),
                      "Whether the boundary of a body may contact itself "
                      "(pairs of triangles sharing a vertex never count).");
    prm.declare_entry(
      "Collision tolerance",
      "1e-6",
      dealii::Patterns::Double(0.),
      "Impenetrability mode: distance tolerance (absolute length) of the "
      "continuous collision detection; primitives closer than this count as "
      "touching. Must be positive, at most a thousandth of the bodies' "
      "shortest boundary edge, and at least 2^-45 times the largest "
      "coordinate of the bodies and obstacles (round-off).");
    prm.leave_subsection();
  }



  void
  ContactParameters::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Contact");
    mode              = parse_mode(prm.get("Mode"));
    penalty_parameter = prm.get_double("Penalty parameter");
    self_contact      = prm.get_bool("Self contact");
    ccd_tolerance     = prm.get_double("Collision tolerance");
    prm.leave_subsection();
    AssertThrow(mode != Mode::penalty || penalty_parameter > 0.,
                dealii::ExcMessage(
                  "Contact: the penalty parameter must be positive."));
    AssertThrow(ccd_tolerance > 0.,
                dealii::ExcMessage(
                  "Contact: the collision tolerance must be positive."));
    // No setting may be silently ignored.
    const ContactParameters defaults;
    const std::string       with = " (Mode = " + mode_name(mode) + ").";
    if (mode != Mode::penalty &&
        penalty_parameter != defaults.penalty_parameter)
      throw std::runtime_error(
        "Contact/Penalty parameter: only Mode = penalty uses it" + with);
    if (mode != Mode::impenetrability &&
        ccd_tolerance != defaults.ccd_tolerance)
      throw std::runtime_error(
        "Contact/Collision tolerance: only Mode = impenetrability uses it" +
        with);
    if (mode == Mode::none && self_contact)
      throw std::runtime_error(
        "Contact/Self contact: there is no contact at all" + with);
  }



  bool
  ContactParameters::is_default() const
  {
    const ContactParameters defaults;
    return mode == defaults.mode &&
           penalty_parameter == defaults.penalty_parameter &&
           self_contact == defaults.self_contact &&
           ccd_tolerance == defaults.ccd_tolerance;
  }



  std::string
  ContactParameters::mode_name(const Mode mode)
  {
    switch (mode)
      {
        case Mode::none:
          return "none";
        case Mode::penalty:
          return "penalty";
        case Mode::impenetrability:
          return "impenetrability";
      }
    return "none";
  }



  ContactParameters::Mode
  ContactParameters::parse_mode(const std::string &name)
  {
    if (name == "none")
      return Mode::none;
    if (name == "penalty")
      return Mode::penalty;
    if (name == "impenetrability")
      return Mode::impenetrability;
    AssertThrow(false,
                dealii::ExcMessage("Contact: unknown mode '" + name +
                                   "' (none, penalty or impenetrability)."));
    return Mode::none;
  }
} // namespace estep
