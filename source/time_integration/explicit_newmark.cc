#include <deal.II/base/parameter_handler.h>

#include <estep/base/parallel_blocks.h>
#include <estep/time_integration/explicit_newmark.h>
#include <estep/time_integration/integrator_registry.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace estep
{
  ExplicitNewmark::ExplicitNewmark(const MechanicalSystem &system,
                                   const double            time_step)
    : TimeIntegrator(system)
    , dt(time_step)
  {
    if (!(time_step > 0.) || !std::isfinite(time_step))
      throw std::invalid_argument("The time step must be positive and finite.");
  }



  std::string
  ExplicitNewmark::name() const
  {
    return "explicit newmark";
  }



  void
  ExplicitNewmark::initialize(const double  t0,
                              const Vector &q0,
                              const Vector &v0)
  {
    t = t_previous = t0;
    q = q_old = q0;
    v = v_old = v0;
    gradient_buffer.reinit(q0.size());
    acceleration.reinit(q0.size());
    compute_acceleration(q, acceleration);
  }



  void
  ExplicitNewmark::compute_acceleration(const Vector &x, Vector &a)
  {
    system.kept_gradient(x, gradient_buffer);
    ++n_gradients;
    const Vector &inverse_mass = system.inverse_mass();
    for_each_kept_range(system, [&](const BlockRange kept) {
      for (unsigned int i = kept.begin; i < kept.end; ++i)
        a[i] = -inverse_mass[i] * gradient_buffer[i];
    });
  }



  void
  ExplicitNewmark::step(const double t_limit)
  {
    const double remaining = t_limit - t;
    if (!(remaining > 0.))
      return;
    // End on t_limit with the last step, stretched if need be by the
    // round-off that the sum of the earlier steps accumulated (up to 1e-6
    // dt), never followed by a step of round-off length.
    const double tau = (remaining < dt * (1. + 1e-6)) ? remaining : dt;

    // On several MPI ranks, the coordinates this rank keeps alone
    // (MechanicalSystem::kept_coordinates()).
    for_each_kept_range(system, [&](const BlockRange kept) {
      for (unsigned int i = kept.begin; i < kept.end; ++i)
        {
          q_old[i] = q[i];
          v_old[i] = v[i];
          q[i] += tau * v[i] + 0.5 * tau * tau * acceleration[i];
          v[i] += 0.5 * tau * acceleration[i];
        }
    });
    compute_acceleration(q, acceleration);
    for_each_kept_range(system, [&](const BlockRange kept) {
      for (unsigned int i = kept.begin; i < kept.end; ++i)
        v[i] += 0.5 * tau * acceleration[i];
    });
    const bool finite = all_finite(system, {&q, &v});

    t_previous = t;
    t          = (tau == remaining) ? t_limit : t + tau;
    count_step();
    if (!finite)
      {
        std::ostringstream message;
        message << "The state became non-finite at t = " << t
                << ": the time step is beyond the stability limit.";
        throw UnstableRun(message.str());
      }
  }



  void
  ExplicitNewmark::complete_state()
  {
    for (Vector *x : {&q, &v, &q_old, &v_old, &acceleration})
      system.complete_state(*x);
  }



  Snapshot
  ExplicitNewmark::dense_output(const double time) const
  {
    return hermite_dense_output(time, q_old, v_old);
  }



  Snapshot
  ExplicitNewmark::dense_state(const double time) const
  {
    return hermite_dense_output(time, q_old, v_old, false);
  }



  std::vector<Counter>
  ExplicitNewmark::counters() const
  {
    return {{"steps", steps}, {"gradient evaluations", n_gradients}};
  }



  void
  ExplicitNewmark::save_state(StateWriter &out) const
  {
    TimeIntegrator::save_state(out);
    out.put_vector(acceleration);
    out.put_vector(q_old);
    out.put_vector(v_old);
    out.put(n_gradients);
  }



  void
  ExplicitNewmark::load_state(StateReader &in)
  {
    TimeIntegrator::load_state(in);
    in.get_vector(acceleration);
    in.get_vector(q_old);
    in.get_vector(v_old);
    n_gradients = in.get<std::uint64_t>();
    gradient_buffer.reinit(q.size());
  }



  namespace
  {
    void
    declare_explicit_newmark_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Explicit Newmark");
      prm.declare_entry(
        "Time step",
        "1e-3",
        dealii::Patterns::Double(0.,
                                 dealii::Patterns::Double::max_double_value),
        "The fixed time step; at least about a million units of "
        "round-off of the End time.");
      prm.leave_subsection();
    }

    std::unique_ptr<TimeIntegrator>
    create_explicit_newmark(dealii::ParameterHandler &prm,
                            const MechanicalSystem   &system)
    {
      prm.enter_subsection("Explicit Newmark");
      const double dt = prm.get_double("Time step");
      prm.leave_subsection();
      require_resolvable_time_step(prm, "Explicit Newmark/Time step", dt);
      return std::make_unique<ExplicitNewmark>(system, dt);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_INTEGRATOR(
  "explicit newmark",
  "the explicit Newmark method (beta = 0, gamma = 1/2; velocity Verlet) at a "
  "fixed time step (subsection Explicit Newmark).",
  estep::declare_explicit_newmark_parameters,
  estep::create_explicit_newmark)
