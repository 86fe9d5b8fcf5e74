#include <deal.II/base/parameter_handler.h>

#include <estep/io/trajectory_norm.h>

#include <cmath>

namespace estep
{
  void
  TrajectoryNorm::after_step(const TimeIntegrator &integrator)
  {
    const double a = integrator.previous_time(), b = integrator.time();
    const double half = 0.5 * (b - a), centre = 0.5 * (a + b);
    const double nodes[3]   = {-std::sqrt(0.6), 0., std::sqrt(0.6)};
    const double weights[3] = {5. / 9., 8. / 9., 5. / 9.};
    for (unsigned int k = 0; k < 3; ++k)
      {
        const Snapshot s = integrator.dense_state(centre + half * nodes[k]);
        integral += half * weights[k] * (s.q.norm_sqr() + s.v.norm_sqr());
      }
  }

  void
  TrajectoryNorm::save_state(StateWriter &out) const
  {
    out.put(integral);
  }

  void
  TrajectoryNorm::resume(StateReader &in)
  {
    integral = in.get<double>();
  }

  bool
  TrajectoryNorm::runs_on_every_rank() const
  {
    return true;
  }

  double
  TrajectoryNorm::h1_norm() const
  {
    return std::sqrt(integral);
  }



  void
  TrajectoryNorm::add_to_summary(JsonObject &summary) const
  {
    summary.add("h1 norm", h1_norm());
  }



  namespace
  {
    std::unique_ptr<Postprocessor>
    create_trajectory_norm(dealii::ParameterHandler &,
                           const PostprocessorContext &)
    {
      return std::make_unique<TrajectoryNorm>();
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "h1 norm",
  "the H1 norm of the trajectory, (integral |q|^2 + |q'|^2 dt)^(1/2), in "
  "summary.json.",
  nullptr,
  estep::create_trajectory_norm)
