#include <estep/implicit/implicit_integrator.h>

#include <cmath>
#include <stdexcept>

namespace estep
{
  ImplicitIntegrator::ImplicitIntegrator(const MechanicalSystem   &system,
                                         const ImplicitParameters &parameters)
    : TimeIntegrator(system)
    , settings(parameters)
  {
    settings.check();
    if (!system.has_hessian())
      throw std::invalid_argument(
        "Time integration/Method: the implicit integrators need the Hessian "
        "(tangent stiffness) of the system, and the system <" +
        system.name() + "> provides none.");
  }



  const ImplicitParameters &
  ImplicitIntegrator::parameters() const
  {
    return settings;
  }



  void
  ImplicitIntegrator::begin_step()
  {
    q_old = q;
    v_old = v;
  }



  void
  ImplicitIntegrator::check_finite() const
  {
    for (unsigned int i = 0; i < q.size(); ++i)
      if (!std::isfinite(q[i]) || !std::isfinite(v[i]))
        throw UnstableRun("The state of " + name() +
                          " became non-finite at t = " + std::to_string(t) +
                          ".");
  }



  Snapshot
  ImplicitIntegrator::dense_output(const double time) const
  {
    return hermite_dense_output(time, q_old, v_old);
  }
} // namespace estep
