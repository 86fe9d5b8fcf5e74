#ifndef estep_tests_argon_h
#define estep_tests_argon_h

// The frozen argon cluster as the application builds it from its default
// parameters.

#include <deal.II/base/parameter_handler.h>

#include <estep/problems/problem.h>

namespace estep::testing
{
  inline Problem
  argon_cluster()
  {
    dealii::ParameterHandler prm;
    declare_problem_parameters(prm);
    prm.enter_subsection("Problem");
    prm.set("System", "argon cluster");
    prm.leave_subsection();
    return create_problem(prm);
  }
} // namespace estep::testing

#endif
