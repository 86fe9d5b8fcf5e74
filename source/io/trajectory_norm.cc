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
        const Snapshot s = integrator.dense_output(centre + half * nodes[k]);
        integral += half * weights[k] * (s.q.norm_sqr() + s.v.norm_sqr());
      }
  }

  double
  TrajectoryNorm::h1_norm() const
  {
    return std::sqrt(integral);
  }
} // namespace estep
