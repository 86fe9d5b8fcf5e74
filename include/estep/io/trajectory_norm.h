#ifndef estep_io_trajectory_norm_h
#define estep_io_trajectory_norm_h

#include <estep/io/postprocessor.h>

namespace estep
{
  /**
   * Accumulates the H1 norm of the trajectory over the run,
   * ||q||_H1(0,T) = ( integral |q(t)|^2 + |q'(t)|^2 dt )^(1/2),
   * step by step with three-point Gauss quadrature on the integrator's dense
   * output: exact for energy-stepping (q linear, q' constant on each step),
   * fifth order for the cubic Hermite output of Newmark.
   *
   * On several MPI processes it runs on every one, each on the whole state,
   * so that an integrator's dense_state() may be collective (its default
   * calls dense_output(), which evaluates V on all processes together).
   */
  class TrajectoryNorm : public Postprocessor
  {
  public:
    void
    after_step(const TimeIntegrator &integrator) override;

    /** The integral so far. */
    void
    save_state(StateWriter &out) const override;

    void
    resume(StateReader &in) override;

    /** Adds "h1 norm". */
    void
    add_to_summary(JsonObject &summary) const override;

    /** True: see the class. */
    bool
    runs_on_every_rank() const override;

    /** The H1 norm accumulated so far. */
    double
    h1_norm() const;

  private:
    double integral = 0.;
  };
} // namespace estep

#endif
