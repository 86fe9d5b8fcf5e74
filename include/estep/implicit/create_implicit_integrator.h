#ifndef estep_implicit_create_implicit_integrator_h
#define estep_implicit_create_implicit_integrator_h

#include <estep/time_integration/time_integrator.h>

#include <memory>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /** The method names create_implicit_integrator() accepts, separated by "|"
   * (for a Patterns::Selection). */
  std::string
  implicit_method_names();

  /**
   * The implicit integrator @p method ("ida bdf", "arkode midpoint", "arkode
   * irk" or "energy momentum") for @p system, with the settings of the
   * subsection "Implicit integrators" of @p prm (declared by
   * declare_implicit_parameters(), at the current level of @p prm) and the
   * time step @p time_step (fixed step of "arkode midpoint" and "energy
   * momentum", first step of the adaptive "ida bdf" and "arkode irk").
   *
   * The system must provide a Hessian (MechanicalSystem::has_hessian(), e.g.
   * ElasticBodyWithHessian); "energy momentum" needs an ElasticBody. Throws
   * std::invalid_argument with a clear message otherwise, or for an unknown
   * method.
   */
  std::unique_ptr<TimeIntegrator>
  create_implicit_integrator(const std::string              &method,
                             const dealii::ParameterHandler &prm,
                             const MechanicalSystem         &system,
                             const double                    time_step);
} // namespace estep

#endif
