// A user's own time integrator as an estep plugin: the symplectic Euler
// method, v += -dt M^-1 grad V(q), then q += dt v, at a fixed time step.
// Choose it with `set Method = symplectic euler` in `Time integration`; its
// step is `Time integration/Symplectic Euler/Time step`.
#include <deal.II/base/parameter_handler.h>

#include <estep/time_integration/integrator_registry.h>

#include <cmath>
#include <stdexcept>

namespace
{
  class SymplecticEuler : public estep::TimeIntegrator
  {
  public:
    SymplecticEuler(const estep::MechanicalSystem &system, const double dt)
      : estep::TimeIntegrator(system)
      , dt(dt)
    {}

    std::string
    name() const override
    {
      return "symplectic euler";
    }

    void
    initialize(const double         t0,
               const estep::Vector &q0,
               const estep::Vector &v0) override
    {
      t = t_previous = t0;
      q = q_old = q0;
      v = v_old = v0;
      gradient.reinit(q0.size());
    }

    void
    step(const double t_limit) override
    {
      // The last step before t_limit is stretched by the round-off that the
      // sum of the earlier steps accumulated, rather than followed by a step
      // of round-off length.
      const double remaining = t_limit - t;
      const double tau       = remaining < dt * (1. + 1e-6) ? remaining : dt;
      q_old                  = q;
      v_old                  = v;
      system.gradient(q, gradient);
      ++n_gradients;
      const estep::Vector &inverse_mass = system.inverse_mass();
      for (unsigned int i = 0; i < q.size(); ++i)
        {
          v[i] -= tau * inverse_mass[i] * gradient[i];
          q[i] += tau * v[i];
          if (!std::isfinite(q[i]) || !std::isfinite(v[i]))
            throw estep::UnstableRun("symplectic euler: the state became "
                                     "non-finite; reduce the time step.");
        }
      t_previous = t;
      t          = (tau == remaining) ? t_limit : t + tau;
      count_step();
    }

    /** Between two steps: the cubic Hermite interpolant of the step's ends. */
    estep::Snapshot
    dense_output(const double time) const override
    {
      return hermite_dense_output(time, q_old, v_old);
    }

    std::vector<estep::Counter>
    counters() const override
    {
      return {{"steps", n_steps()}, {"gradient evaluations", n_gradients}};
    }

    /** For checkpoints: the base class stores t, q, v and the step
     * statistics; this integrator adds what it keeps beyond them. */
    void
    save_state(estep::StateWriter &out) const override
    {
      TimeIntegrator::save_state(out);
      out.put_vector(q_old);
      out.put_vector(v_old);
      out.put(n_gradients);
    }

    void
    load_state(estep::StateReader &in) override
    {
      TimeIntegrator::load_state(in);
      in.get_vector(q_old);
      in.get_vector(v_old);
      n_gradients = in.get<std::uint64_t>();
      gradient.reinit(q.size());
    }

  private:
    const double  dt;
    estep::Vector q_old, v_old, gradient;
    std::uint64_t n_gradients = 0;
  };

  void
  declare_symplectic_euler_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Symplectic Euler");
    prm.declare_entry("Time step",
                      "1e-3",
                      dealii::Patterns::Double(0.),
                      "The fixed time step; must be positive.");
    prm.leave_subsection();
  }

  std::unique_ptr<estep::TimeIntegrator>
  create_symplectic_euler(dealii::ParameterHandler      &prm,
                          const estep::MechanicalSystem &system)
  {
    prm.enter_subsection("Symplectic Euler");
    const double dt = prm.get_double("Time step");
    prm.leave_subsection();
    if (!(dt > 0.))
      throw std::runtime_error(
        "Time integration/Symplectic Euler/Time step: must be positive.");
    return std::make_unique<SymplecticEuler>(system, dt);
  }
} // namespace

ESTEP_REGISTER_INTEGRATOR("symplectic euler",
                          "the symplectic Euler method at a fixed time step "
                          "(subsection Symplectic Euler): the example plugin.",
                          declare_symplectic_euler_parameters,
                          create_symplectic_euler)
