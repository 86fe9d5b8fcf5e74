#ifndef estep_time_integration_joint_reflection_h
#define estep_time_integration_joint_reflection_h

#include <estep/systems/mechanical_system.h>

#include <vector>

namespace estep
{
  /**
   * The normal of one reflection off constraints touching at the same
   * instant together: n = sum_k lambda_k n_k, with lambda >= 0 the
   * multipliers of the velocity's projection (in the metric of M) onto the
   * velocities that part every pair,
   *
   *   w = N^T v + G lambda >= 0,   lambda >= 0,   lambda . w = 0,
   *   G = N^T M^-1 N   (N = [n_1 ... n_K], the normals of @p normals),
   *
   * a non-negative least-squares problem, min |M^-1/2 (M v + N lambda)|,
   * solved by Lawson and Hanson's active-set method, which ends after
   * finitely many steps, keeps only independent normals in its set (there
   * are at most as many as the coordinates the normals touch), and whose
   * result does not depend on which of several equal normals it took.
   *
   * v + M^-1 n is the projection, and the reflection off n,
   * v - 2 (n . v) / (n . M^-1 n) M^-1 n (a reflection like any other: it
   * keeps the kinetic energy, and the momenta when every n_k does), is its
   * mirror image: every pair that approached parts at 2 w_k - n_k . v > 0,
   * and every pair held by the projection (lambda_k > 0) that parted now
   * approaches at the rate it parted at.
   *
   * Each n_k must be oriented so that n_k . v > 0 parts its pair. Zero if
   * no pair approaches, or if @p normals is empty.
   */
  Vector
  joint_reflection_normal(const std::vector<SparseNormal> &normals,
                          const Vector                    &v,
                          const Vector                    &inverse_mass);
} // namespace estep

#endif
