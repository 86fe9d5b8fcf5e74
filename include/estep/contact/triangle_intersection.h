#ifndef estep_contact_triangle_intersection_h
#define estep_contact_triangle_intersection_h

#include <estep/contact/geometry.h>
#include <estep/contact/predicates.h>

#include <array>

namespace estep
{
  namespace contact
  {
    /** What the intersection of two closed triangles is. */
    enum class IntersectionKind
    {
      /** The triangles are disjoint (also returned if one triangle is
         degenerate). */
      none,
      /** A single point, the triangles are not coplanar (e.g. a vertex touching
         a face). */
      point,
      /** A segment of positive length, the triangles are not coplanar. */
      segment,
      /** The triangles are coplanar and intersect (in a point, a segment or an
         area). */
      coplanar
    };

    /**
     * Where an end point of the intersection segment comes from: the point
     * where the edge (edge[0], edge[1]) of triangle @p edge_triangle meets the
     * plane of the other triangle (the face, 1 - edge_triangle): X = V[edge[0]]
     * + t (V[edge[1]] - V[edge[0]]). Triangle and vertex numbers refer to the
     * caller's order of the arguments.
     */
    struct SegmentEndPoint
    {
      /** 0 or 1: the argument whose edge produced the point. */
      unsigned int edge_triangle = 0;
      /** Local vertex numbers (0, 1, 2) of the edge, in the direction t runs.
       */
      std::array<unsigned int, 2> edge = {{0, 1}};
      /** Edge parameter of the point, in [0, 1]. */
      double t = 0.;
    };

    /**
     * The intersection of two closed triangles.
     *
     * Invariants: the kind is exact (decided by exact orientation predicates
     * only); for kind point and segment, A and B are the end points (A == B for
     * a point), ordered along the direction n0 x n1 of the intersection line of
     * the canonical triangles (see intersect_triangles()), and source[0],
     * source[1] say which edge and face produced A and B. For none and
     * coplanar, A, B and source are unspecified.
     */
    struct TriangleIntersection
    {
      IntersectionKind               kind = IntersectionKind::none;
      Point3                         A    = {{0., 0., 0.}};
      Point3                         B    = {{0., 0., 0.}};
      std::array<SegmentEndPoint, 2> source;
    };

    /**
     * Intersect the closed triangles @p T0 and @p T1.
     *
     * The computation is canonicalised: each triangle's vertices are sorted
     * lexicographically and the two triangles are ordered lexicographically
     * before anything is computed, so the result (kind, the points A and B bit
     * for bit, and the physical edges and faces that produced them) does not
     * depend on the order of the vertices nor on the order of the two
     * arguments; only the labels in SegmentEndPoint follow the caller's
     * numbering.
     *
     * The kind is exact. An end point on an edge crossing the other plane
     * strictly is computed as a + t (b - a) with t = d_a / (d_a - d_b) (signed
     * distances in floating point, t clamped to [0, 1]); an end point at a
     * vertex lying exactly on the other plane is that vertex. Degenerate
     * triangles (collinear vertices) give kind none.
     */
    TriangleIntersection
    intersect_triangles(const Triangle3 &T0, const Triangle3 &T1);

    /**
     * Whether the closed triangles intersect (exact; same predicates as
     * intersect_triangles(), without constructing the points).
     */
    bool
    triangles_intersect(const Triangle3 &T0, const Triangle3 &T1);

    /**
     * Exact test of two coplanar closed triangles for intersection, by exact 2D
     * predicates on the projection along the axis on which T0 does not
     * degenerate. Precondition: the six points are coplanar. Returns false if a
     * triangle is degenerate.
     */
    bool
    coplanar_triangles_intersect(const Triangle3 &T0, const Triangle3 &T1);

    /**
     * Whether the closed triangles @p T0 and @p T1 cross, rather than only
     * touch: whether the bodies they bound overlap next to where they meet.
     * Each triangle bounding a body turns counterclockwise seen from outside
     * it (its normal (b - a) x (c - a) points out). @p T1_bounds_a_body false
     * makes T1 two-sided: a surface with no inside.
     *
     * Exact (orientation predicates only). Triangles that meet touch if
     * - they meet in a single point (a vertex on a face, two edges across
     *   each other);
     * - T1 lies on the outer closed side of T0's plane, or T0 on the outer
     *   closed side of T1's plane (on either side, if T1 is two-sided): an
     *   edge lying on a face;
     * - they are coplanar and face opposite ways (flush faces), or face the
     *   same way with disjoint interiors (faces side by side), or T1 is
     *   two-sided.
     * Otherwise they cross. The rules are local: a body lying inside another
     * and touching it from within touches at every pair; whether such a
     * body is nested takes a point of it off the other's boundary.
     */
    bool
    triangles_cross(const Triangle3 &T0,
                    const Triangle3 &T1,
                    const bool       T1_bounds_a_body);
  } // namespace contact
} // namespace estep

#endif
