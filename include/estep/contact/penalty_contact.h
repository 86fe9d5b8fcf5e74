#ifndef estep_contact_penalty_contact_h
#define estep_contact_penalty_contact_h

#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/triangle_intersection.h>

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace estep
{
  namespace contact
  {
    /**
     * g = |A - B|^2 for the intersection segment [A, B] of two triangles
     * (units: length^2), and optionally its gradient with respect to the 18
     * vertex coordinates (T0's three vertices, then T1's, each x, y, z). g = 0
     * with zero gradient unless the kind is segment (none, point, and coplanar
     * overlap by convention).
     *
     * Each end point X is the intersection of an edge (a, b) of one triangle
     * with the plane of the other (vertices p, q, r): X = a + t (b - a), t =
     * d_a / (d_a - d_b), d_x = n . (x - p), n = (q - p) x (r - p); the gradient
     * is the exact derivative of this formula (one-sided where an end point
     * switches generator, e.g. a vertex on the plane).
     */
    double
    squared_intersection_length(const Triangle3        &T0,
                                const Triangle3        &T1,
                                std::array<double, 18> *gradient = nullptr);

    /**
     * The penalty contact energy I(q) = 1 / (2 eps) * sum over pairs of surface
     * triangles g(q), g = |A - B|^2 for intersecting pairs (see
     * squared_intersection_length()); units: length^2 / eps, so eps has units
     * length^2 / energy.
     *
     * Conventions: pairs of triangles that share a vertex index are excluded
     * (neighbours on one surface); coplanar overlaps and single-point contacts
     * contribute 0. The energy is invariant under rigid motions; the gradient
     * has zero net force and torque.
     *
     * The coordinates q are point-major: point i at q[3i], q[3i + 1], q[3i +
     * 2]. A bounding volume hierarchy of the triangles finds candidate pairs;
     * it is refitted at every evaluation and rebuilt every rebuild_interval()
     * evaluations. Evaluations therefore modify internal caches: one object
     * must not be evaluated from several threads at once.
     */
    class PenaltyContact
    {
    public:
      /**
       * @p triangles: vertex-index triples of the surface triangles (e.g. the
       * boundary faces of an elastic body); @p eps > 0 the penalty parameter.
       * Throws std::invalid_argument for eps <= 0 or a repeated index within a
       * triangle.
       */
      PenaltyContact(std::vector<TriangleIndices> triangles, const double eps);

      /** I(q). n is the size of q (3 * number of points). */
      double
      energy(const double *q, const std::size_t n) const;

      /** g += grad I(q); returns I(q). */
      double
      add_gradient(const double *q, const std::size_t n, double *g) const;

      /** Number of triangle pairs with a segment intersection (g > 0 possible)
       * at q. */
      unsigned int
      n_intersecting_pairs(const double *q, const std::size_t n) const;

      /** The penalty parameter. */
      double
      get_eps() const
      {
        return eps;
      }

      /** The surface triangles. */
      const std::vector<TriangleIndices> &
      get_triangles() const
      {
        return bvh.get_triangles();
      }

      /**
       * Exclude every pair of triangles i, j with groups[i] == groups[j] (e.g.
       * the body number of each triangle, to switch self-contact off). An
       * empty vector (the default) excludes nothing beyond pairs that share a
       * vertex. Throws std::invalid_argument if the size differs from the
       * number of triangles.
       */
      void
      set_exclusion_groups(std::vector<unsigned int> groups);

      /** The exclusion groups as last set (empty: none). The broad phase
       * leaves out the pairs they exclude, as those that share a vertex. */
      const std::vector<unsigned int> &
      get_exclusion_groups() const
      {
        return bvh.get_exclusion_groups();
      }

      /** The broad phase's hierarchy as last refitted: a flight starts from
       * a copy of it, whose topology it keeps. */
      const BoundingVolumeHierarchy &
      hierarchy() const
      {
        return bvh;
      }

      /** Rebuild the hierarchy every this many refits (default 64; 0:
       * never). */
      void
      set_rebuild_interval(const unsigned int interval)
      {
        bvh.set_rebuild_interval(interval);
      }

      /**
       * I along one free flight, I(q + s v) for 0 <= s <= s_max. The candidate
       * pairs are found once, from boxes swept over the whole flight; each
       * evaluation then visits only those pairs. Copies q and v.
       */
      class Flight
      {
      public:
        /** I(q + s v); s must lie in [0, s_max] (not checked; outside, pairs
         * may be missed). */
        double
        value(const double s) const;

        /** I(q + s v) and dI/ds = grad I . v. */
        std::pair<double, double>
        value_and_derivative(const double s) const;

        /** Number of candidate pairs of the flight (swept boxes overlap). */
        std::size_t
        n_candidate_pairs() const
        {
          return pairs.size();
        }

        /** Number of pairs with a segment intersection at q + s v. */
        unsigned int
        n_intersecting_pairs(const double s) const;

        /** The end of the flight interval the candidates are valid for. */
        double
        get_s_max() const
        {
          return s_max;
        }

      private:
        friend class PenaltyContact;
        Flight() = default;

        double
        evaluate(const double s, double *derivative, unsigned int *count) const;

        const PenaltyContact                              *contact = nullptr;
        std::vector<double>                                q, v;
        double                                             s_max = 0.;
        std::vector<std::pair<unsigned int, unsigned int>> pairs;
      };

      /** The sums over candidate pairs run on the threads and MPI ranks in
       * blocks of this many pairs, added in block order (see
       * sum_over_shared_blocks() in distributed_blocks.h). */
      static constexpr unsigned int pairs_per_block = 64;

      /**
       * I(q + s v) summed over the candidate @p pairs only; dI/ds into
       * @p derivative and the number of intersecting pairs into @p count
       * (both optional). Shared by the flights of the penalty term.
       * Collective on several MPI ranks if @p pairs fill more than one block.
       */
      double
      sum_along_line(
        const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
        const double                                             *q,
        const double                                             *v,
        const double                                              s,
        double                                                   *derivative,
        unsigned int                                             *count) const;

      /** Prepare evaluations along q + s v, 0 <= s <= s_max (s_max >= 0,
       * finite). */
      Flight
      flight(const double     *q,
             const double     *v,
             const std::size_t n,
             const double      s_max) const;

    private:
      double
      evaluate(const double     *q,
               const std::size_t n,
               double           *g,
               unsigned int     *count) const;

      double                                                     eps;
      mutable BoundingVolumeHierarchy                            bvh;
      mutable std::vector<std::pair<unsigned int, unsigned int>> pairs;
    };
  } // namespace contact
} // namespace estep

#endif
