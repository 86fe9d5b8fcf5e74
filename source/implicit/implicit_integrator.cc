#include <estep/implicit/implicit_integrator.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace estep
{
  ImplicitIntegrator::ImplicitIntegrator(const MechanicalSystem   &system,
                                         const ImplicitParameters &parameters)
    : TimeIntegrator(system)
    , settings(parameters)
  {
    settings.check();
    record_unread_settings(settings.unread_entries);
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
  ImplicitIntegrator::save_state(StateWriter &out) const
  {
    TimeIntegrator::save_state(out);
    out.put_vector(q_old);
    out.put_vector(v_old);
    const std::vector<Counter> counts = counters();
    out.put(static_cast<std::uint64_t>(counts.size()));
    for (const auto &[name, count] : counts)
      {
        out.put(name);
        out.put(count);
      }
  }



  void
  ImplicitIntegrator::load_state(StateReader &in)
  {
    TimeIntegrator::load_state(in);
    const double        time = t, time_before = t_previous;
    const Vector        position = q, velocity = v;
    const std::uint64_t n_steps  = steps;
    const double        smallest = smallest_step, largest = largest_step;
    initialize(time, position, velocity);
    t_previous    = time_before;
    steps         = n_steps;
    smallest_step = smallest;
    largest_step  = largest;
    in.get_vector(q_old);
    in.get_vector(v_old);

    resumed_counts.clear();
    const std::vector<Counter> after_restart = counters();
    const auto                 n             = in.get<std::uint64_t>();
    for (std::uint64_t i = 0; i < n; ++i)
      {
        const std::string name  = in.get_string();
        const auto        count = in.get<std::uint64_t>();
        std::uint64_t     now   = 0;
        for (const auto &[other, value] : after_restart)
          if (other == name)
            now = value;
        if (name != "steps")
          resumed_counts.emplace_back(name, count - now);
      }
  }



  std::vector<Counter>
  ImplicitIntegrator::with_resumed_counts(std::vector<Counter> counts) const
  {
    for (auto &[name, count] : counts)
      for (const auto &[resumed, offset] : resumed_counts)
        if (resumed == name)
          count += offset;
    return counts;
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
        {
          std::ostringstream message;
          message << "The state of " << name()
                  << " became non-finite at t = " << t << ".";
          throw UnstableRun(message.str());
        }
  }



  Snapshot
  ImplicitIntegrator::dense_output(const double time) const
  {
    return hermite_dense_output(time, q_old, v_old);
  }



  Snapshot
  ImplicitIntegrator::dense_state(const double time) const
  {
    return hermite_dense_output(time, q_old, v_old, false);
  }
} // namespace estep
