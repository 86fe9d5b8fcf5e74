#include <estep/contact/point_in_surface.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  namespace contact
  {
    double
    squared_distance_to_triangle(const Point3 &p, const Triangle3 &t)
    {
      // The closest point by the Voronoi regions of the vertices, the edges
      // and the face (as in Ericson, Real-Time Collision Detection, 5.1.5).
      const Point3 ab = minus(t[1], t[0]), ac = minus(t[2], t[0]);
      const Point3 ap           = minus(p, t[0]);
      const auto   squared_norm = [](const Point3 &a) { return dot(a, a); };
      const auto along = [&](const Point3 &a, const Point3 &d, const double s) {
        return Point3{{a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]}};
      };
      const double d1 = dot(ab, ap), d2 = dot(ac, ap);
      if (d1 <= 0. && d2 <= 0.)
        return squared_norm(ap);
      const Point3 bp = minus(p, t[1]);
      const double d3 = dot(ab, bp), d4 = dot(ac, bp);
      if (d3 >= 0. && d4 <= d3)
        return squared_norm(bp);
      const double vc = d1 * d4 - d3 * d2;
      if (vc <= 0. && d1 >= 0. && d3 <= 0.)
        return squared_norm(minus(p, along(t[0], ab, d1 / (d1 - d3))));
      const Point3 cp = minus(p, t[2]);
      const double d5 = dot(ab, cp), d6 = dot(ac, cp);
      if (d6 >= 0. && d5 <= d6)
        return squared_norm(cp);
      const double vb = d5 * d2 - d1 * d6;
      if (vb <= 0. && d2 >= 0. && d6 <= 0.)
        return squared_norm(minus(p, along(t[0], ac, d2 / (d2 - d6))));
      const double va = d3 * d6 - d5 * d4;
      if (va <= 0. && d4 - d3 >= 0. && d5 - d6 >= 0.)
        return squared_norm(minus(
          p,
          along(t[1], minus(t[2], t[1]), (d4 - d3) / ((d4 - d3) + (d5 - d6)))));
      // Inside the face: the distance to the plane.
      const Point3 n = cross(ab, ac);
      const double h = dot(n, ap);
      return h * h / squared_norm(n);
    }



    double
    solid_angle(const Point3 &p, const Triangle3 &t)
    {
      const Point3 a = minus(t[0], p), b = minus(t[1], p), c = minus(t[2], p);
      const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)),
                   lc        = std::sqrt(dot(c, c));
      const double numerator = dot(a, cross(b, c));
      const double denominator =
        la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
      // The normal (b - a) x (c - a) points away from p when a . (b x c) is
      // positive: p sees the triangle from behind, from inside a closed
      // outward surface.
      return 2. * std::atan2(numerator, denominator);
    }



    PointAndSurface
    locate_point(const Point3                       &p,
                 const double                       *x,
                 const std::vector<TriangleIndices> &all_triangles,
                 const std::vector<unsigned int>    &triangles,
                 const double                        near)
    {
      double closest = std::numeric_limits<double>::infinity();
      for (const unsigned int i : triangles)
        {
          closest = std::min(
            closest,
            squared_distance_to_triangle(p, triangle_at(x, all_triangles[i])));
          if (closest <= near * near)
            return {std::sqrt(closest),
                    std::numeric_limits<double>::quiet_NaN()};
        }
      double angle = 0.;
      for (const unsigned int i : triangles)
        angle += solid_angle(p, triangle_at(x, all_triangles[i]));
      return {std::sqrt(closest), angle / (4. * M_PI)};
    }
  } // namespace contact
} // namespace estep
