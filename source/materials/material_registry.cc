#include <deal.II/base/parameter_handler.h>

#include <estep/base/exception_text.h>
#include <estep/materials/material_registry.h>

#include <cmath>
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



  namespace
  {
    /**
     * Throws, naming @p what, unless the material's functions agree with each
     * other at a few stretches J: finite values, f' the derivative of f and
     * f'' that of f' (against central differences), the values inside the
     * ranges of a small interval about J, and a stress-free reference state,
     * f'(1) = -c. A material of one's own that gets one of these wrong would
     * otherwise run without a word: the search trusts what it is told.
     */
    void
    check_material(const Material &material, const std::string &what)
    {
      // Ten digits: a derivative that fails the check may differ from its
      // difference quotient in the sixth.
      const auto number = [](const double x) { return message_number(x, 10); };
      const double c    = material.quadratic_modulus();
      const auto   fail = [&](const double J, const std::string &text) {
        throw std::runtime_error(what + ": at J = " + number(J) + ", " + text +
                                 " (doc/extending.md, \"A material\").");
      };
      for (const double J : {0.5, 0.8, 1., 1.25, 2.})
        {
          const double f   = material.volumetric_energy(J);
          const double df  = material.volumetric_derivative(J);
          const double d2f = material.volumetric_second_derivative(J);
          if (!std::isfinite(f) || !std::isfinite(df) || !std::isfinite(d2f))
            fail(J,
                 "f, f' and f'' are not all finite: " + number(f) + ", " +
                   number(df) + ", " + number(d2f));
          const double d          = 1e-4 * J;
          const double f_quotient = (material.volumetric_energy(J + d) -
                                     material.volumetric_energy(J - d)) /
                                    (2. * d);
          const double df_quotient = (material.volumetric_derivative(J + d) -
                                      material.volumetric_derivative(J - d)) /
                                     (2. * d);
          // The differences' truncation, d^2 f''' / 6, and round-off,
          // eps |f| / d, lie far below these bounds.
          const double scale = std::abs(df) + c + J * std::abs(d2f);
          if (!(std::abs(df - f_quotient) <= 1e-6 * scale))
            fail(J,
                 "volumetric_derivative() returns f' = " + number(df) +
                   " where the central difference of volumetric_energy() "
                   "gives " +
                   number(f_quotient) + ": f' is not the derivative of f");
          if (!(J * std::abs(d2f - df_quotient) <= 1e-5 * scale))
            fail(J,
                 "volumetric_second_derivative() returns f'' = " + number(d2f) +
                   " where the central difference of "
                   "volumetric_derivative() gives " +
                   number(df_quotient) + ": f'' is not the derivative of f'");
          const Interval around{J * (1. - 1e-3), J * (1. + 1e-3)};
          const auto     check_range = [&](const std::string &function,
                                       const Interval    &range,
                                       const auto        &point_function) {
            for (const double x : {around.lower, J, around.upper})
              if (const double value = point_function(x);
                  !(range.lower <= value && value <= range.upper))
                fail(J,
                     function + " over [" + number(around.lower) + ", " +
                       number(around.upper) + "] is [" + number(range.lower) +
                       ", " + number(range.upper) +
                       "], which misses the value " + number(value) + " at " +
                       number(x) +
                       ": a range must hold every value in its interval");
          };
          check_range("volumetric_energy_range()",
                      material.volumetric_energy_range(around),
                      [&](const double x) {
                        return material.volumetric_energy(x);
                      });
          check_range("volumetric_derivative_range()",
                      material.volumetric_derivative_range(around),
                      [&](const double x) {
                        return material.volumetric_derivative(x);
                      });
          check_range("volumetric_second_derivative_range()",
                      material.volumetric_second_derivative_range(around),
                      [&](const double x) {
                        return material.volumetric_second_derivative(x);
                      });
        }
      if (const double stress = material.volumetric_derivative(1.) + c;
          !(std::abs(stress) <= 1e-8 * c))
        fail(1.,
             "f'(1) + c = " + number(stress) +
               " where it must be 0: the reference state is not stress-free "
               "(its first Piola stress is (f'(1) + c) I)");
    }
  } // namespace



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
    check_material(*choice.material, section + "/Model = " + model);
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
