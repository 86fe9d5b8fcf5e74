#include <deal.II/base/parameter_handler.h>

#include <estep/systems/mechanical_system.h>
#include <estep/time_integration/integrator_registry.h>
#include <estep/time_integration/time_loop.h>

#include <sstream>
#include <stdexcept>

namespace estep
{
  PluginRegistry<IntegratorFactory> &
  integrator_registry()
  {
    static PluginRegistry<IntegratorFactory> registry("time integrator");
    return registry;
  }



  void
  declare_integrator_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry(
      "Method",
      "energy stepping",
      dealii::Patterns::Selection(integrator_registry().names()),
      "The time integrator, one of the registered integrators; each reads "
      "its own subsection:" +
        integrator_registry().descriptions());
    integrator_registry().declare_parameters(prm);
  }



  std::vector<std::string>
  ignored_integrator_settings(dealii::ParameterHandler &prm)
  {
    const std::string        method = prm.get("Method");
    std::vector<std::string> warnings;
    for (const UnreadSubsection &unread : changed_unread_subsections(
           prm, integrator_registry().declarations(), {method}))
      warnings.push_back(
        unread_subsection_text("Time integration",
                               unread,
                               "Time integration/Method = " + method) +
        "; its settings are ignored.");
    return warnings;
  }



  void
  require_resolvable_time_step(dealii::ParameterHandler &prm,
                               const std::string        &entry,
                               const double              time_step)
  {
    const double start_time = prm.get_double("Start time");
    const double end_time   = prm.get_double("End time");
    const double resolution = time_resolution(start_time, end_time);
    if (time_step < resolution)
      {
        std::ostringstream message;
        message << "Time integration/" << entry << ": " << time_step
                << " is below the resolution of the run's times (" << resolution
                << " up to End time = " << end_time
                << "): the steps could not advance the time accurately; "
                << "take a larger step.";
        throw std::runtime_error(message.str());
      }
  }



  std::unique_ptr<TimeIntegrator>
  create_integrator(dealii::ParameterHandler &prm,
                    const MechanicalSystem   &system)
  {
    const std::string method     = prm.get("Method");
    auto              integrator = integrator_registry()
                        .get(method, "Time integration/Method")
                        .create(prm, system);
    if (system.has_constraints() && !integrator->follows_constraint_events())
      throw std::runtime_error(
        "Time integration/Method: " + method +
        " cannot keep bodies apart by impenetrability constraints "
        "(Contact/Mode = impenetrability), whose events it does not "
        "follow; use energy stepping, or Contact/Mode = penalty.");
    return integrator;
  }
} // namespace estep
