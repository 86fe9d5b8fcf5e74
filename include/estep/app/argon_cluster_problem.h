#ifndef estep_app_argon_cluster_problem_h
#define estep_app_argon_cluster_problem_h

#include <estep/app/problem.h>

namespace estep
{
  /**
   * The frozen argon cluster (Hairer, Lubich and Wanner, Geometric Numerical
   * Integration, section I.4): argon atoms with a Lennard-Jones pair potential.
   * The parameter file gives the data in SI-derived units (kg, K, nm, m/s); the
   * run uses reduced units: length sigma, energy epsilon, mass m, time tau =
   * sigma sqrt(m / epsilon) (2.1596 ps for argon), so all times and energy
   * steps of the parameter file are in tau and epsilon.
   */
  namespace ArgonClusterProblem
  {
    /** Declare the subsection "Argon cluster". */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Build the cluster and its initial state in reduced units. */
    Problem
    create(dealii::ParameterHandler &prm);
  } // namespace ArgonClusterProblem
} // namespace estep

#endif
