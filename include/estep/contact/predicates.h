#ifndef estep_contact_predicates_h
#define estep_contact_predicates_h

#include <estep/contact/geometry.h>

#include <array>

namespace estep
{
  namespace contact
  {
    /** A point of the plane. */
    using Point2 = std::array<double, 2>;

    /**
     * Exact sign of the 2D orientation determinant det[b - a, c - a]: +1 if a,
     * b, c turn counterclockwise (c left of the directed line a -> b), -1 if
     * clockwise, 0 if collinear. Same convention as CGAL::orientation(p, q, r)
     * and Shewchuk's orient2d.
     *
     * The determinant is first evaluated in floating point with Shewchuk's
     * error bound
     * (|det - fl(det)| <= (3 + 16 u) u (|detleft| + |detright|), u = 2^-53);
     * only when the floating-point value cannot be trusted is the sign computed
     * exactly with floating-point expansion arithmetic. The result is exact for
     * all finite inputs as long as no product of coordinate differences
     * overflows or underflows (|differences| between about 1e-145 and 1e145, or
     * exactly zero).
     */
    int
    orient2d(const Point2 &a, const Point2 &b, const Point2 &c);

    /**
     * Exact sign of det[b - a, c - a, d - a] = (d - a) . ((b - a) x (c - a)):
     * +1 if d lies on the side of the plane through a, b, c into which the
     * normal (b - a) x (c - a) points, -1 on the other side, 0 if the four
     * points are coplanar (or a, b, c collinear). Same convention as
     * CGAL::orientation(p, q, r, s); opposite sign to Shewchuk's orient3d.
     *
     * Floating-point filter with Shewchuk's bound (7 + 56 u) u * permanent,
     * exact fallback with expansion arithmetic; same range of validity as
     * orient2d() (products of three differences must neither overflow nor
     * underflow: |differences| in about [1e-97, 1e97]).
     */
    int
    orient3d(const Point3 &a,
             const Point3 &b,
             const Point3 &c,
             const Point3 &d);

    /**
     * The exact-arithmetic path of orient3d() alone (no filter). For tests and
     * for counting how often the filter fails.
     */
    int
    orient3d_exact(const Point3 &a,
                   const Point3 &b,
                   const Point3 &c,
                   const Point3 &d);

    /** The exact-arithmetic path of orient2d() alone (no filter). */
    int
    orient2d_exact(const Point2 &a, const Point2 &b, const Point2 &c);
  } // namespace contact
} // namespace estep

#endif
