#ifndef estep_app_elastic_body_problem_h
#define estep_app_elastic_body_problem_h

#include <estep/app/problem.h>

namespace estep
{
  /**
   * One neo-Hookean body (the spinning cube, or any mesh estep can
   * build): the subsection "Elastic body" with its mesh, material, initial
   * velocity (a rigid motion or a parsed function) and tracked point. Units are
   * whatever consistent units the parameters are given in (the spinning cube
   * is dimensionless).
   */
  namespace ElasticBodyProblem
  {
    /** Declare the subsection "Elastic body". */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Build the body in its reference configuration with the initial velocity.
     */
    Problem
    create(dealii::ParameterHandler &prm);
  } // namespace ElasticBodyProblem
} // namespace estep

#endif
