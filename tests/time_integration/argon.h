#ifndef estep_tests_argon_h
#define estep_tests_argon_h

// The frozen argon cluster as the application builds it from its default
// parameters.

#include <deal.II/base/parameter_handler.h>

#include <estep/app/argon_cluster_problem.h>

namespace estep::testing
{
  inline Problem
  argon_cluster()
  {
    dealii::ParameterHandler prm;
    ArgonClusterProblem::declare_parameters(prm);
    return ArgonClusterProblem::create(prm);
  }
} // namespace estep::testing

#endif
