#ifndef estep_contact_penalty_flight_h
#define estep_contact_penalty_flight_h

#include <estep/base/interval.h>
#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/penalty_contact.h>

#include <cstddef>
#include <utility>
#include <vector>

namespace estep
{
  namespace contact
  {
    /** Enclosures of the penalty energy and of its slope over a parameter
     * interval of a flight. */
    struct PenaltyEnclosure
    {
      /** Holds every I(q + s v), s in [a, b]. */
      Interval value;
      /** Holds every dI/ds(q + s v), s in [a, b]. */
      Interval derivative;
    };

    /**
     * Rigorous enclosure of g = |A - B|^2 (see squared_intersection_length())
     * and of dg/ds for the triangles T0, T1 whose vertices move as x + s w, s
     * in [a, b]. @p x0, @p w0 hold T0's three vertices and velocities, @p x1,
     * @p w1 T1's (each 9 numbers, vertex-major).
     *
     * Method (interval arithmetic with forward derivatives in s, every vertex
     * an interval x + [a, b] w): the signed distances of each triangle's
     * vertices to the other's plane, the direction d = n0 x n1 of the common
     * line, and for each triangle the end points of its chord on that line,
     * as coordinates u = d . X of the edge/plane crossings X = x_i + t (x_j -
     * x_i), t = d_i / (d_i - d_j). Edges are taken as possible generators when
     * their end distances may have opposite signs; where the sign pattern is
     * not decided the chord ends are hulls over the possible generators (and
     * over the edge end points when t is not bounded). Then len = min(hi_0,
     * hi_1) - max(lo_0, lo_1) and g = max(len, 0)^2 / |d|^2, with interval
     * min/max whose derivative is the hull of the derivatives of the
     * candidates that can be the extremum. Pairs whose vertices all lie on
     * one side of the other's plane give [0, 0]. Nearly parallel planes (|d|^2
     * not bounded away from 0) give the hull [0, diameter^2] of the
     * intersection of the two swept boxes and an unbounded slope.
     *
     * The result contains the exact values; it is then widened by a margin
     * for the round-off of the floating-point evaluation of g in
     * squared_intersection_length() (256 u L / sin(angle), L the largest
     * coordinate, on the end points) and of its slope (relative 1e-12). Where
     * the generators of A and B do not change on [a, b] the enclosure
     * tightens linearly as b - a -> 0.
     */
    PenaltyEnclosure
    enclose_squared_intersection_length(const double *x0,
                                        const double *w0,
                                        const double *x1,
                                        const double *w1,
                                        const double  a,
                                        const double  b);

    /**
     * The penalty energy I of a PenaltyContact along one free flight q + s v,
     * s >= 0, with the point values and slopes of PenaltyContact::Flight and,
     * in addition, rigorous enclosures over parameter intervals (what the
     * certified first-crossing search of energy-stepping needs).
     *
     * Candidate pairs: for enclose(a, b), the pairs whose boxes swept over [a,
     * b] overlap (BoundingVolumeHierarchy::build_swept(), enlarged by a
     * round-off margin), minus excluded pairs (shared vertex, exclusion
     * groups); every other pair is disjoint on [a, b] and contributes [0, 0].
     * For value(s), the pairs of the last swept interval if it holds s,
     * otherwise the pairs of the boxes at q + s v. Each candidate pair's g is
     * enclosed by enclose_squared_intersection_length().
     *
     * Copies q and v; the PenaltyContact must outlive this object. Not
     * thread-safe (cached candidates).
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

      /** Enclosures of I and dI/ds over [a, b], 0 <= a <= b. */
      PenaltyEnclosure
      enclose(const double a, const double b) const;

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
      /** Make the candidate list valid on [a, b]. */
      void
      update_candidates(const double a, const double b) const;

      double
      evaluate(const double s, double *derivative, unsigned int *count) const;

      const PenaltyContact                                      &contact;
      std::vector<double>                                        q, v;
      double                                                     max_q = 0.;
      double                                                     max_v = 0.;
      mutable BoundingVolumeHierarchy                            bvh;
      mutable bool                                               cached = false;
      mutable double                                             cache_a = 0.;
      mutable double                                             cache_b = 0.;
      mutable std::vector<std::pair<unsigned int, unsigned int>> pairs;
      mutable std::vector<double>                                scratch;
    };
  } // namespace contact
} // namespace estep

#endif
