// A plugin library that registers a time integrator under a name estep has
// already ("energy stepping"): loading it must fail with one clear message.
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/integrator_registry.h>

namespace
{
  std::unique_ptr<estep::TimeIntegrator>
  create_impostor(dealii::ParameterHandler &, const estep::MechanicalSystem &)
  {
    return nullptr;
  }
} // namespace

ESTEP_REGISTER_INTEGRATOR("energy stepping",
                          "an impostor",
                          nullptr,
                          create_impostor)
