#include <estep/systems/rigid_body_motion.h>

#include <stdexcept>

namespace estep
{
  RigidBodyMotion
  rigid_body_motion(const Vector      &inverse_mass,
                    const Vector      &q,
                    const Vector      &v,
                    const unsigned int first_point,
                    const unsigned int n_points)
  {
    if (3 * (std::size_t(first_point) + n_points) > q.size() ||
        q.size() != v.size() || q.size() != inverse_mass.size())
      throw std::invalid_argument("rigid_body_motion: sizes do not match");
    RigidBodyMotion r;
    double          momentum[3] = {0., 0., 0.};
    for (unsigned int i = first_point; i < first_point + n_points; ++i)
      {
        const double m = 1. / inverse_mass[3 * i];
        r.mass += m;
        for (unsigned int c = 0; c < 3; ++c)
          {
            r.centre[c] += m * q[3 * i + c];
            momentum[c] += m * v[3 * i + c];
          }
      }
    if (!(r.mass > 0.))
      return r;
    for (unsigned int c = 0; c < 3; ++c)
      {
        r.centre[c] /= r.mass;
        r.velocity[c] = momentum[c] / r.mass;
      }
    for (unsigned int i = first_point; i < first_point + n_points; ++i)
      {
        const double m    = 1. / inverse_mass[3 * i];
        const double x[3] = {q[3 * i] - r.centre[0],
                             q[3 * i + 1] - r.centre[1],
                             q[3 * i + 2] - r.centre[2]};
        const double u[3] = {v[3 * i] - r.velocity[0],
                             v[3 * i + 1] - r.velocity[1],
                             v[3 * i + 2] - r.velocity[2]};
        r.angular[0] += m * (x[1] * u[2] - x[2] * u[1]);
        r.angular[1] += m * (x[2] * u[0] - x[0] * u[2]);
        r.angular[2] += m * (x[0] * u[1] - x[1] * u[0]);
      }
    for (double &a : r.angular)
      a /= r.mass;
    return r;
  }
} // namespace estep
