#ifndef estep_contact_continuous_collision_h
#define estep_contact_continuous_collision_h

#include <estep/contact/geometry.h>

#include <array>

namespace estep
{
  namespace contact
  {
    /** Controls of the conservative continuous collision detection. */
    struct CcdSettings
    {
      /**
       * Distance tolerance delta (length units, absolute): a sub-box of the
       * parameter domain whose image lies within [-delta, delta]^3 (round-off
       * bound included) is reported as a contact. Pairs that come closer than
       * delta (in every coordinate) may therefore be reported although they
       * never touch: false positives, never false negatives.
       */
      double tolerance = 1e-6;
      /** Cap on the number of boxes examined; reaching it reports a contact
       * (conservative). */
      unsigned int max_iterations = 100000;
    };

    /** Outcome of one continuous collision query. */
    struct CcdResult
    {
      /** Whether the primitives may touch for some t in [0, 1]. */
      bool hit = false;
      /**
       * If hit: a time in [0, 1] no later than the first exact contact time
       * (equal to it up to the subdivision; the primitives are within the
       * tolerance of each other at a time no later than this one or the
       * iteration cap was reached).
       */
      double time = 1.;
      /** Number of boxes examined. */
      unsigned int n_iterations = 0;
      /** Whether the iteration cap decided the answer. */
      bool capped = false;
    };

    /**
     * The largest coordinate magnitude at which the CCD of tolerance
     * @p tolerance can still certify a contact: 2^45 tolerance (1e-6 gives
     * about 3.5e7). The CCD widens every value by its round-off bound, 2^-46
     * times the largest coordinate of the query, and reports a contact only
     * for a box whose widened range lies within the tolerance; beyond this
     * limit the bound is more than half the tolerance, and a query that meets
     * a contact subdivides until the iteration cap instead.
     */
    constexpr double
    ccd_coordinate_limit(const double tolerance)
    {
      return 0x1p45 * tolerance;
    }

    /**
     * Relative volume below which the four points of a CCD query count as
     * coplanar (see ccd_query_is_non_degenerate()): 2^-42, about 2.3e-13 or
     * 2,048 units of round-off u = 2^-53.
     */
    constexpr double non_degeneracy_threshold = 0x1p-42;

    /**
     * Whether a CCD query (vertex-face or edge-edge, points x0, x1, x2, x3 in
     * the order of vertex_face_ccd() and edge_edge_ccd()) is non-degenerate:
     * at t = 0 and at t = 1 the four points are robustly non-coplanar,
     *
     *   |det[x1 - x0, x2 - x0, x3 - x0]| > 2^-42 L^3,
     *
     * with L the longest of the six distances between the points. The ratio
     * (six times the tetrahedron's volume over L^3, at most 1 by Hadamard's
     * inequality) does not depend on the order of the points and is invariant
     * under translation, rotation and scaling; it is small exactly when all
     * four points lie within a small fraction of L of one plane.
     *
     * Every degeneracy visible at the ends of the step makes it vanish,
     * exactly or within rounding: contact or near contact at t = 0 or t = 1,
     * coplanar motion, parallel edges (two parallel lines span a plane), a
     * collapsed edge or triangle, three collinear points; so does data that is
     * one of these up to the rounding of its construction (parallel edges
     * whose rotated coordinates differ by 1e-17, for instance). The threshold
     * is about 40 times the determinant's own round-off (at most about 9 u
     * times its permanent, which is at most 3^(3/2) L^3), so the
     * floating-point evaluation used here decides as exact arithmetic would
     * except for ratios within about 60 u of 2^-42 (on the sample queries the
     * nearest values are 2.4e-16 and 1.05e-12). Degeneracies that arise only
     * between the ends (edges parallel at the moment of contact, a vertex
     * meeting an edge of the face) are not detected.
     */
    bool
    ccd_query_is_non_degenerate(const std::array<Point3, 4> &start,
                                const std::array<Point3, 4> &end);

    /**
     * Conservative continuous collision detection of a point and a triangle
     * moving linearly from time 0 to time 1: x(t) = x0 + t (x1 - x0) for every
     * vertex. @p start and @p end hold the point, then the triangle's three
     * vertices, at t = 0 and t = 1.
     *
     * Method (inclusion-based root finding, as in Wang et al. 2021): the
     * function F(t, u, v) = p(t) - (1 - u - v) a(t) - u b(t) - v c(t) is
     * multilinear in (t, u, v), so its range over a box of parameters is the
     * hull of its 8 corner values; these are computed in floating point and
     * widened by a proven round-off bound (2^-46 times the largest coordinate
     * magnitude). Boxes whose widened range excludes 0 in some coordinate, or
     * along the face normal at the box's middle time, are discarded; the
     * others are subdivided, earliest time first; the first box whose range
     * lies within the tolerance gives the reported time (its lower t). Before
     * any box, the query is rejected if the four points provably never become
     * coplanar in [0, 1] (all Bernstein coefficients of the cubic
     * det[b - a, c - a, p - a](t) of one strict sign, with a round-off
     * bound). Hence no false negatives: every exact contact lies in a box that
     * is never discarded, and makes the four points coplanar.
     */
    CcdResult
    vertex_face_ccd(const std::array<Point3, 4> &start,
                    const std::array<Point3, 4> &end,
                    const CcdSettings           &settings = CcdSettings());

    /**
     * Conservative continuous collision detection of two edges (a0, a1) and
     * (b0, b1) moving linearly; @p start and @p end hold a0, a1, b0, b1 at t =
     * 0 and t = 1. Same method and guarantees as vertex_face_ccd(), with F(t,
     * u, v) = a(t, u) - b(t, v) (the normal direction is the cross product of
     * the edges).
     */
    CcdResult
    edge_edge_ccd(const std::array<Point3, 4> &start,
                  const std::array<Point3, 4> &end,
                  const CcdSettings           &settings = CcdSettings());
  } // namespace contact
} // namespace estep

#endif
