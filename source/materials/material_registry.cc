#include <deal.II/base/parameter_handler.h>

#include <estep/materials/material_registry.h>

#include <stdexcept>

namespace estep
{
  PluginRegistry<MaterialFactory> &
  material_registry()
  {
    static PluginRegistry<MaterialFactory> registry("material");
    return registry;
  }



  void
  declare_material_parameters(dealii::ParameterHandler &prm)
  {
    const double max = dealii::Patterns::Double::max_double_value;
    prm.declare_entry("Model",
                      "neo-Hookean",
                      dealii::Patterns::Selection(material_registry().names()),
                      "The strain energy of the body, one of the registered "
                      "materials; each reads a subsection of its own:" +
                        material_registry().descriptions());
    prm.declare_entry(
      "Density",
      "0.100",
      dealii::Patterns::Double(0., max),
      "Mass density per unit reference volume; must be positive.");
    material_registry().declare_parameters(prm);
  }



  MaterialChoice
  parse_material_parameters(dealii::ParameterHandler &prm,
                            const std::string        &section)
  {
    MaterialChoice choice;
    choice.density = prm.get_double("Density");
    if (!(choice.density > 0.))
      throw std::runtime_error(section + "/Density: must be positive.");
    const std::string model = prm.get("Model");
    const auto &plugin = material_registry().get(model, section + "/Model");
    for (const UnreadSubsection &unread : changed_unread_subsections(
           prm, material_registry().declarations(), {model}))
      throw std::runtime_error(
        unread_subsection_text(section, unread, section + "/Model = " + model) +
        "; a setting there would be ignored.");
    try
      {
        choice.material = plugin.create(prm);
      }
    catch (const std::runtime_error &error)
      {
        // The plugin names its entry relative to its own subsection.
        throw std::runtime_error(section + "/" + error.what());
      }
    return choice;
  }



  void
  declare_lame_constants(dealii::ParameterHandler &prm,
                         const std::string        &section)
  {
    const double max = dealii::Patterns::Double::max_double_value;
    prm.enter_subsection(section);
    prm.declare_entry("Lambda",
                      "0.0100",
                      dealii::Patterns::Double(0., max),
                      "Lame constant lambda0 (stress units).");
    prm.declare_entry("Mu",
                      "0.0066",
                      dealii::Patterns::Double(0., max),
                      "Shear modulus mu0 (stress units); must be positive.");
    prm.leave_subsection();
  }



  LameConstants
  parse_lame_constants(dealii::ParameterHandler &prm,
                       const std::string        &section)
  {
    prm.enter_subsection(section);
    const LameConstants constants{prm.get_double("Lambda"),
                                  prm.get_double("Mu")};
    prm.leave_subsection();
    if (!(constants.mu > 0.))
      throw std::runtime_error(section + "/Mu: must be positive.");
    return constants;
  }
} // namespace estep
