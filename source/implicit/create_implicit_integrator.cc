#include <deal.II/base/parameter_handler.h>

#include <estep/fem/elastic_body.h>
#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/create_implicit_integrator.h>
#include <estep/implicit/energy_momentum.h>
#include <estep/implicit/ida_bdf.h>

#include <stdexcept>

namespace estep
{
  std::string
  implicit_method_names()
  {
    return "ida bdf|arkode midpoint|arkode irk|energy momentum";
  }



  std::unique_ptr<TimeIntegrator>
  create_implicit_integrator(const std::string              &method,
                             const dealii::ParameterHandler &prm,
                             const MechanicalSystem         &system,
                             const double                    time_step)
  {
    const ImplicitParameters parameters = parse_implicit_parameters(prm);
    if (!system.has_hessian())
      throw std::invalid_argument(
        "Time integration/Method = " + method +
        ": the implicit integrators need the Hessian (tangent stiffness) of "
        "the system, and the system <" +
        system.name() + "> provides none.");
    if (method == "ida bdf")
      return std::make_unique<IdaBdf>(system, parameters, time_step);
    if (method == "arkode midpoint")
      return std::make_unique<ArkodeRungeKutta>(
        system, parameters, ArkodeRungeKutta::Method::midpoint, time_step);
    if (method == "arkode irk")
      return std::make_unique<ArkodeRungeKutta>(system,
                                                parameters,
                                                ArkodeRungeKutta::Method::dirk,
                                                time_step);
    if (method == "energy momentum")
      {
        const auto *body = dynamic_cast<const ElasticBody *>(&system);
        if (body == nullptr)
          throw std::invalid_argument(
            "Time integration/Method = energy momentum works on a single "
            "elastic body, and the system <" +
            system.name() + "> is not one.");
        return std::make_unique<EnergyMomentum>(*body, parameters, time_step);
      }
    throw std::invalid_argument("Unknown implicit method <" + method +
                                ">; choose one of: " + implicit_method_names() +
                                ".");
  }
} // namespace estep
