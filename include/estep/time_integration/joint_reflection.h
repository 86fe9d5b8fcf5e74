#ifndef estep_time_integration_joint_reflection_h
#define estep_time_integration_joint_reflection_h

#include <estep/systems/mechanical_system.h>

#include <vector>

namespace estep
{
  /**
   * The change of momentum N lambda of the velocity's projection (in the
   * metric of M) onto the velocities that part or hold every pair of
   * @p normals: v + M^-1 N lambda, with
   *
   *   w = N^T v + G lambda >= 0,   lambda >= 0,   lambda . w = 0,
   *   G = N^T M^-1 N   (N = [n_1 ... n_K]),
   *
   * a non-negative least-squares problem, min |M^-1/2 (M v + N lambda)|,
   * solved by Lawson and Hanson's active-set method, which ends after
   * finitely many steps, keeps only independent normals in its set (there
   * are at most as many as the coordinates the normals touch), and whose
   * result does not depend on which of several equal normals it took.
   *
   * Each n_k must be oriented so that n_k . v > 0 parts its pair. Zero if
   * no pair approaches, or if @p normals is empty.
   */
  Vector
  parting_projection_normal(const std::vector<SparseNormal> &normals,
                            const Vector                    &v,
                            const Vector                    &inverse_mass);

  /**
   * The normal n of one reflection off constraints touching at the same
   * instant together, v - 2 (n . v) / (n . M^-1 n) M^-1 n (a reflection like
   * any other: it keeps the kinetic energy, and the momenta when every n_k
   * does).
   *
   * The projection v_p = v + M^-1 N lambda (parting_projection_normal())
   * parts or holds every pair, but takes kinetic energy. It is given back
   * along d = M^-1 N mu, mu >= 0 the multipliers that make every pair that
   * approached part at least at the speed it approached at, and hold every
   * other, (G mu)_k >= max(-n_k . v, 0) (the same complementarity problem:
   * a restitution of each pair): v' = v_p + tau d, tau > 0 the root of
   * |v'|_M = |v|_M. Every pair then parts or is held, N^T v' = w + tau G mu
   * >= 0, and every pair that approached parts; v' - v = M^-1 n with
   * n = N (lambda + tau mu), so that v' is the reflection off n.
   *
   * Where the pairs jam (no mu >= 0 makes them all part, as for a point
   * between two walls) or round-off leaves pairs approaching after it, n =
   * N lambda if a pair that approached would not part, or if the
   * projection's mirror image v + 2 M^-1 N lambda leaves none approaching
   * faster. That mirror image parts every pair that approached, but makes
   * the pairs that the projection held while they parted approach.
   *
   * Zero if no pair approaches, or if @p normals is empty.
   */
  Vector
  joint_reflection_normal(const std::vector<SparseNormal> &normals,
                          const Vector                    &v,
                          const Vector                    &inverse_mass);
} // namespace estep

#endif
