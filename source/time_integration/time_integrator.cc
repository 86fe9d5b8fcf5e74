#include <estep/base/parallel_blocks.h>
#include <estep/time_integration/time_integrator.h>

#include <algorithm>
#include <limits>

namespace estep
{
  TimeIntegrator::TimeIntegrator(const MechanicalSystem &system)
    : system(system)
  {}

  void
  TimeIntegrator::count_step()
  {
    const double dt = t - t_previous;
    smallest_step   = (steps == 0) ? dt : std::min(smallest_step, dt);
    largest_step    = (steps == 0) ? dt : std::max(largest_step, dt);
    ++steps;
  }


  Snapshot
  TimeIntegrator::hermite_dense_output(const double  time,
                                       const Vector &q_old,
                                       const Vector &v_old,
                                       const bool    with_energies) const
  {
    Snapshot     snapshot;
    const double tau = t - t_previous;
    snapshot.t       = time;
    if (tau <= 0. || q_old.size() != q.size())
      {
        snapshot.q = q;
        snapshot.v = v;
      }
    else
      {
        // Cubic Hermite basis on [t_previous, t] in x in [0, 1].
        const double x   = (time - t_previous) / tau;
        const double h00 = (1 + 2 * x) * (1 - x) * (1 - x),
                     h10 = x * (1 - x) * (1 - x), h01 = x * x * (3 - 2 * x),
                     h11 = x * x * (x - 1);
        const double d00 = 6 * x * (x - 1), d10 = (1 - x) * (1 - 3 * x),
                     d01 = -6 * x * (x - 1), d11 = x * (3 * x - 2);
        snapshot.q.reinit(q.size());
        snapshot.v.reinit(q.size());
        for (unsigned int i = 0; i < q.size(); ++i)
          {
            snapshot.q[i] = h00 * q_old[i] + h10 * tau * v_old[i] + h01 * q[i] +
                            h11 * tau * v[i];
            snapshot.v[i] =
              (d00 * q_old[i] + d01 * q[i]) / tau + d10 * v_old[i] + d11 * v[i];
          }
      }
    system.complete_state(snapshot.q);
    system.complete_state(snapshot.v);
    if (with_energies)
      {
        snapshot.kinetic_energy   = kinetic_energy(system, snapshot.v);
        snapshot.potential_energy = system.energy(snapshot.q);
      }
    else
      snapshot.kinetic_energy = snapshot.potential_energy =
        std::numeric_limits<double>::quiet_NaN();
    snapshot.terraced_potential_energy = snapshot.potential_energy;
    return snapshot;
  }



  Snapshot
  TimeIntegrator::dense_state(const double time) const
  {
    return dense_output(time);
  }



  void
  TimeIntegrator::complete_state()
  {}



  double
  TimeIntegrator::current_kinetic_energy() const
  {
    const Vector &inverse_mass = system.inverse_mass();
    return 0.5 * sum_over_coordinate_blocks<double>(
                   system, [&](const unsigned int b) {
                     const BlockRange dofs  = block_range(b, v.size());
                     double           twice = 0.;
                     for (unsigned int i = dofs.begin; i < dofs.end; ++i)
                       twice += v[i] * v[i] / inverse_mass[i];
                     return twice;
                   });
  }



  void
  TimeIntegrator::add_energies_to_summary(JsonObject &) const
  {}



  std::vector<std::string>
  TimeIntegrator::warnings() const
  {
    return unread_settings;
  }



  void
  TimeIntegrator::record_unread_settings(std::vector<std::string> sentences)
  {
    unread_settings = std::move(sentences);
  }



  void
  TimeIntegrator::save_state(StateWriter &out) const
  {
    out.put(t);
    out.put(t_previous);
    out.put_vector(q);
    out.put_vector(v);
    out.put(steps);
    out.put(smallest_step);
    out.put(largest_step);
  }



  void
  TimeIntegrator::load_state(StateReader &in)
  {
    t          = in.get<double>();
    t_previous = in.get<double>();
    in.get_vector(q);
    in.get_vector(v);
    steps         = in.get<std::uint64_t>();
    smallest_step = in.get<double>();
    largest_step  = in.get<double>();
  }



  bool
  TimeIntegrator::follows_constraint_events() const
  {
    return false;
  }



  std::string
  TimeIntegrator::conserved_energy() const
  {
    return "T + V";
  }



  double
  relative_drift(const double a, const double b, const double scale)
  {
    return std::abs(b - a) / (std::abs(a) > 1e-14 * scale ? std::abs(a) : 1.);
  }
} // namespace estep
