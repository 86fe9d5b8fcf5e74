#ifndef estep_time_integration_integrator_registry_h
#define estep_time_integration_integrator_registry_h

#include <estep/base/plugin_registry.h>
#include <estep/time_integration/time_integrator.h>

#include <memory>
#include <string>
#include <vector>

namespace estep
{
  /**
   * The create function of a time integrator plugin: reads the integrator's
   * parameters (declared by its declare_parameters inside the subsection `Time
   * integration`, with @p prm in that subsection) and returns the integrator
   * of @p system, not yet initialised. Throws std::runtime_error naming the
   * entry on bad input, or when the system lacks what the integrator needs.
   */
  using IntegratorFactory =
    std::unique_ptr<TimeIntegrator>(dealii::ParameterHandler &,
                                    const MechanicalSystem &);

  /** The registered time integrators. */
  PluginRegistry<IntegratorFactory> &
  integrator_registry();

  /**
   * Declare, in the current subsection (`Time integration`), `Method` (a
   * Selection of the registered integrators) and every integrator's own
   * parameters.
   */
  void
  declare_integrator_parameters(dealii::ParameterHandler &prm);

  /** Warnings for the subsections of the current one (`Time integration`)
   * that only integrators other than the one chosen by `Method` read and
   * that the input sets: their settings are ignored. */
  std::vector<std::string>
  ignored_integrator_settings(dealii::ParameterHandler &prm);

  /** Throws, naming @p entry, unless the fixed time step @p time_step can be
   * stepped through between the run's `Start time` and `End time` (read
   * from the current subsection, `Time integration`): it must be at least
   * their time_resolution(). */
  void
  require_resolvable_time_step(dealii::ParameterHandler &prm,
                               const std::string        &entry,
                               const double              time_step);

  /** The integrator chosen by `Method`, from the current subsection. */
  std::unique_ptr<TimeIntegrator>
  create_integrator(dealii::ParameterHandler &prm,
                    const MechanicalSystem   &system);
} // namespace estep

/**
 * Register a time integrator: its name (the value of `Time
 * integration/Method`), a description, the function declaring its parameters
 * and its create function (an IntegratorFactory). An integrator's source file
 * ends with this.
 */
#define ESTEP_REGISTER_INTEGRATOR(name, description, declare, create) \
  ESTEP_REGISTER_PLUGIN(                                              \
    ::estep::integrator_registry(), name, description, declare, create)

#endif
