#ifndef estep_contact_penalty_flight_h
#define estep_contact_penalty_flight_h

#include <estep/base/interval.h>
#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/penalty_contact.h>
#include <estep/systems/free_flight.h>
#include <estep/systems/line_taylor_form.h>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace estep
{
  namespace contact
  {
    /**
     * The second-order form of g = |A - B|^2 (see
     * squared_intersection_length()) for the triangles T0, T1 whose vertices
     * move as x + s w, over [m - r, m + r]. @p x0, @p w0 hold T0's three
     * vertices and velocities, @p x1, @p w1 T1's (each 9 numbers,
     * vertex-major).
     *
     * The value and slope at m are those of squared_intersection_length() at
     * the vertices x + m w. The rest follows from the polynomial structure of
     * the intersection along the flight: in coordinates relative to a vertex,
     * the face normals are quadratics and the signed vertex-plane distances D
     * cubics in s, whose coefficients about m are computed with a rounding
     * bound; over the interval they give enclosures of D, D' and D'' (jets).
     * - If every vertex lies on a proven side of the other plane, the
     *   generating edges of each triangle's chord on the common line are
     *   known (the two edges at the vertex alone on its side; which end is
     *   which follows from that vertex's side), and the order of the chord
     *   ends of the two triangles along the line from the sign of the cubic
     *   orient3d of the two generating edges. If all these are proven, g is
     *   smooth on the interval (C^1 where the overlap starts or ends) and C
     *   is the jet enclosure of g'' = d^2/ds^2 |X_B - X_A|^2 with the end
     *   points X = x_i + D_i / (D_i - D_j) (x_j - x_i) (hull with 0 where the
     *   overlap may be empty). Triangles proven on one side of a plane give
     *   g = 0.
     * - Otherwise (a vertex may cross the other plane, or two chord ends may
     *   swap: g has a kink) W is the hull of 0 and of the slopes
     *   d/ds |X_e - X_f|^2 = 2 (X_e - X_f) . (X_e' - X_f') over the pairs of
     *   edges e, f that may generate the end points (their end distances
     *   may have opposite signs), minus g'(m); unbounded if such an edge may
     *   be parallel to the plane it crosses.
     *
     * Round-off of the computed values (stated, not proven): an end point is
     * taken to be within 256 u (L + |e| L / |f|) / sin(phi) of the exact one
     * (4 times the tolerance measured against exact arithmetic in
     * doc/contact.md; L the largest coordinate, |e| the edge, |f| the shortest
     * edge of the face, phi the angle between edge and plane), and its
     * velocity within that error times (|w| / L + |S'| / |S|) (S = D_i - D_j,
     * the rate at which the crossing moves); value_error and slope_error
     * follow for g = |X_B - X_A|^2 and g'.
     */
    LineTaylorForm
    squared_intersection_length_form(const double *x0,
                                     const double *w0,
                                     const double *x1,
                                     const double *w1,
                                     const double  m,
                                     const double  r);

    /**
     * The penalty energy I of a PenaltyContact along one free flight q + s v,
     * s >= 0, with point values and slopes and, in addition, second-order
     * forms over parameter intervals (what the certified first-crossing
     * search of energy-stepping needs).
     *
     * Candidate pairs: for taylor_form(a, b), the pairs whose boxes swept over
     * [a, b] overlap (enlarged by a round-off margin), minus excluded pairs
     * (shared vertex, exclusion groups); every other pair is disjoint on [a,
     * b] and contributes 0. They are filtered from the pairs of a broad phase
     * (BoundingVolumeHierarchy::build_swept()) over a longer interval [a', a'
     * + 4 (b' - a')], rebuilt when a query leaves it; value(s) uses the boxes
     * at q + s v the same way. Each candidate pair contributes
     * squared_intersection_length_form() / (2 eps).
     *
     * Copies q and v; the PenaltyContact must outlive this object. Not
     * thread-safe (cached candidates). On several MPI ranks, every rank
     * holds the same flight and makes the same calls: the ranks share the
     * sums over the candidate pairs (sum_over_shared_blocks()), so that the
     * calls are collective.
     */
    class PenaltyFlight
    {
    public:
      /** The flight of @p contact from @p q with velocity @p v (size n). */
      PenaltyFlight(const PenaltyContact &contact,
                    const double         *q,
                    const double         *v,
                    const std::size_t     n);

      /** I(q + s v), s >= 0. */
      double
      value(const double s) const;

      /** I(q + s v) and dI/ds = grad I . v. */
      std::pair<double, double>
      value_and_derivative(const double s) const;

      /** The second-order form of I about the centre of [a, b], 0 <= a <= b.
       */
      LineTaylorForm
      taylor_form(const double a, const double b) const;

      /** Enclosures of I and dI/ds over [a, b]: taylor_form(a, b).enclosure().
       */
      LineEnclosure
      enclose(const double a, const double b) const;

      /** The round-off bound of I at the start of the flight (value_error of
       * the form at s = 0). */
      double
      value_tolerance() const;

      /** Number of pairs with a segment intersection at q + s v. */
      unsigned int
      n_intersecting_pairs(const double s) const;

      /** Number of candidate pairs of the last broad-phase query. */
      std::size_t
      n_candidate_pairs() const
      {
        return pairs.size();
      }

    private:
      /** Make the candidate list (pairs) valid on [a, b]. */
      void
      update_candidates(const double a, const double b) const;

      double
      evaluate(const double s, double *derivative, unsigned int *count) const;

      const PenaltyContact           &contact;
      std::vector<double>             q, v;
      double                          max_q;
      double                          max_v;
      mutable BoundingVolumeHierarchy bvh;
      mutable bool                    cached  = false;
      mutable double                  cache_a = 0.;
      mutable double                  cache_b = 0.;
      /** The broad phase's pairs, valid on [cache_a, cache_b], in increasing
       * order. */
      mutable std::vector<std::pair<unsigned int, unsigned int>> broad_pairs;
      /** The candidates of the last query. */
      mutable std::vector<std::pair<unsigned int, unsigned int>> pairs;
      /** Boxes of the triangles swept over a query's interval, made when a
       * pair first needs them: swept_boxes[t] is that of query box_query[t]
       * (queries counted by n_queries, from 1). */
      mutable std::vector<BoundingBox>   swept_boxes;
      mutable std::vector<std::uint64_t> box_query;
      mutable std::uint64_t              n_queries = 0;
      mutable std::vector<double>        scratch;
      mutable double                     tolerance = -1.;
    };
  } // namespace contact
} // namespace estep

#endif
