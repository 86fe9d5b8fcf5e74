#ifndef estep_app_colliding_balls_problem_h
#define estep_app_colliding_balls_problem_h

#include <estep/app/problem.h>

namespace estep
{
  /**
   * Two neo-Hookean balls colliding: ball 1 at rest at the
   * origin, ball 2 on the x axis at a gap from it, moving towards it and
   * spinning about the y axis; contact between their boundary surfaces as the
   * subsection "Contact" says (penalty energy or exact impenetrability). The
   * subsection "Colliding balls" holds the geometry, the material and the
   * motion; units are those of the parameters (SI in the examples of
   * parameter_files/).
   */
  namespace CollidingBallsProblem
  {
    /** Declare the subsections "Colliding balls" and "Contact". */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Build the two balls, the contact system and the initial state. */
    Problem
    create(dealii::ParameterHandler &prm);
  } // namespace CollidingBallsProblem
} // namespace estep

#endif
