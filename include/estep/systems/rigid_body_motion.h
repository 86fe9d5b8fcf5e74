#ifndef estep_systems_rigid_body_motion_h
#define estep_systems_rigid_body_motion_h

#include <estep/systems/mechanical_system.h>

#include <array>

namespace estep
{
  /**
   * The rigid part of the motion of a set of points: mass, centre of mass, its
   * velocity, and the angular momentum about the centre of mass divided by the
   * mass (the "Omega" of the colliding-balls figures, units length^2 / time;
   * for a rigid ball of radius R spinning with omega it is 2/5 R^2 omega).
   */
  struct RigidBodyMotion
  {
    /** Total mass. */
    double mass = 0.;
    /** Centre of mass. */
    std::array<double, 3> centre = {{0., 0., 0.}};
    /** Velocity of the centre of mass. */
    std::array<double, 3> velocity = {{0., 0., 0.}};
    /** Angular momentum about the centre of mass, divided by the mass. */
    std::array<double, 3> angular = {{0., 0., 0.}};
  };

  /**
   * The rigid motion of points [first_point, first_point + n_points) of the
   * point-major 3D state (q, v) with the lumped masses 1 / @p inverse_mass.
   */
  RigidBodyMotion
  rigid_body_motion(const Vector      &inverse_mass,
                    const Vector      &q,
                    const Vector      &v,
                    const unsigned int first_point,
                    const unsigned int n_points);
} // namespace estep

#endif
