#ifndef estep_contact_geometry_h
#define estep_contact_geometry_h

#include <array>

namespace estep
{
  namespace contact
  {
    /**
     * @name The vocabulary of the contact geometry
     *
     * Points, triangles and the point numbers of surface triangles, and the
     * few vector operations the contact code computes with (plain floating
     * point; the exact predicates are in predicates.h).
     */
    /** @{ */

    /** A point of 3D space, coordinates in the length unit of the model. */
    using Point3 = std::array<double, 3>;

    /** A triangle of 3D space given by its three vertices. */
    using Triangle3 = std::array<Point3, 3>;

    /** A surface triangle given by three point indices into a point-major
     * coordinate vector. */
    using TriangleIndices = std::array<unsigned int, 3>;

    /** a - b. */
    inline Point3
    minus(const Point3 &a, const Point3 &b)
    {
      return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
    }

    /** The cross product a x b. */
    inline Point3
    cross(const Point3 &a, const Point3 &b)
    {
      return {{a[1] * b[2] - a[2] * b[1],
               a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
    }

    /** The dot product a . b. */
    inline double
    dot(const Point3 &a, const Point3 &b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }

    /** Point @p i of the point-major coordinates @p x. */
    inline Point3
    point_at(const double *x, const unsigned int i)
    {
      return {{x[3 * i], x[3 * i + 1], x[3 * i + 2]}};
    }

    /** The vertices of triangle @p t in the point-major coordinates @p x. */
    inline Triangle3
    triangle_at(const double *x, const TriangleIndices &t)
    {
      return {{point_at(x, t[0]), point_at(x, t[1]), point_at(x, t[2])}};
    }

    /** @} */
  } // namespace contact
} // namespace estep

#endif
