#ifndef estep_contact_continuous_collision_h
#define estep_contact_continuous_collision_h

#include <estep/contact/predicates.h>

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
     * magnitude). Boxes whose widened range excludes 0 in some coordinate are
     * discarded; the others are subdivided, earliest time first; the first box
     * whose range lies within the tolerance gives the reported time (its lower
     * t). Hence no false negatives: every exact contact lies in a box that is
     * never discarded.
     */
    CcdResult
    vertex_face_ccd(const std::array<Point3, 4> &start,
                    const std::array<Point3, 4> &end,
                    const CcdSettings           &settings = CcdSettings());

    /**
     * Conservative continuous collision detection of two edges (a0, a1) and
     * (b0, b1) moving linearly; @p start and @p end hold a0, a1, b0, b1 at t =
     * 0 and t = 1. Same method and guarantees as vertex_face_ccd(), with F(t,
     * u, v) = a(t, u) - b(t, v).
     */
    CcdResult
    edge_edge_ccd(const std::array<Point3, 4> &start,
                  const std::array<Point3, 4> &end,
                  const CcdSettings           &settings = CcdSettings());
  } // namespace contact
} // namespace estep

#endif
