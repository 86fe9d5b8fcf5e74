#ifndef estep_contact_point_in_surface_h
#define estep_contact_point_in_surface_h

#include <estep/contact/geometry.h>

#include <vector>

namespace estep
{
  namespace contact
  {
    /**
     * The squared distance from @p p to the closest point of the (closed,
     * solid) triangle @p t: to its interior, one of its edges or one of its
     * vertices (plain floating point).
     */
    double
    squared_distance_to_triangle(const Point3 &p, const Triangle3 &t);

    /**
     * The signed solid angle that the triangle @p t subtends at @p p
     * (Van Oosterom and Strackee's formula): positive when p lies on the
     * side its normal (t[1] - t[0]) x (t[2] - t[0]) points away from, at
     * most 2 pi in magnitude, 0 for p in its plane.
     */
    double
    solid_angle(const Point3 &p, const Triangle3 &t);

    /**
     * Where the point @p p lies with respect to the closed surface made of
     * the triangles @p triangles (point numbers into the point-major
     * coordinates @p x), oriented with outward normals.
     */
    struct PointAndSurface
    {
      /** The distance from p to the surface. */
      double distance;
      /** The winding number of the surface about p: 1 inside, 0 outside
       * (up to round-off, which is small when p is far from the surface
       * relative to its triangles' size). */
      double winding_number;
    };

    /**
     * The distance from @p p to the surface of the triangles @p triangles
     * (indices into @p all_triangles) in the coordinates @p x and, if that
     * distance exceeds @p near, the winding number of the surface about p.
     * The search stops at the first triangle closer than @p near: then the
     * distance returned is that triangle's (at most @p near) and the winding
     * number is not computed (NaN).
     */
    PointAndSurface
    locate_point(const Point3                       &p,
                 const double                       *x,
                 const std::vector<TriangleIndices> &all_triangles,
                 const std::vector<unsigned int>    &triangles,
                 const double                        near);
  } // namespace contact
} // namespace estep

#endif
