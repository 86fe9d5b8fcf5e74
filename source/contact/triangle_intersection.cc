#include <estep/contact/triangle_intersection.h>

#include <cmath>
#include <utility>

namespace estep
{
  namespace contact
  {
    namespace
    {
      inline bool
      less_point(const Point3 &a, const Point3 &b)
      {
        if (a[0] != b[0])
          return a[0] < b[0];
        if (a[1] != b[1])
          return a[1] < b[1];
        return a[2] < b[2];
      }

      // perm such that T[perm[0]] <= T[perm[1]] <= T[perm[2]]
      // lexicographically.
      inline std::array<unsigned int, 3>
      sorted_vertices(const Triangle3 &T)
      {
        std::array<unsigned int, 3> p = {{0, 1, 2}};
        if (less_point(T[p[1]], T[p[0]]))
          std::swap(p[0], p[1]);
        if (less_point(T[p[2]], T[p[1]]))
          std::swap(p[1], p[2]);
        if (less_point(T[p[1]], T[p[0]]))
          std::swap(p[0], p[1]);
        return p;
      }

      inline int
      sgn(const int x)
      {
        return (x > 0) - (x < 0);
      }

      // An end point candidate: the edge (a, b) of triangle k (0: P, 1: Q)
      // meeting the plane of the other triangle.
      struct EdgeRef
      {
        unsigned int k, a, b;
      };

      // The vertex that is alone on its side of the other plane (see
      // doc/contact.md): the two edges leaving it cross the other plane (or end
      // on it). Precondition: the signs are neither all equal and non-zero nor
      // all zero.
      inline unsigned int
      alone_vertex(const int s[3])
      {
        unsigned int n_pos = 0, n_neg = 0, i_pos = 0, i_neg = 0, i_zero = 0;
        for (unsigned int i = 0; i < 3; ++i)
          if (s[i] > 0)
            ++n_pos, i_pos = i;
          else if (s[i] < 0)
            ++n_neg, i_neg = i;
          else
            i_zero = i;
        if (n_pos == 1)
          return i_pos;
        if (n_neg == 1)
          return i_neg;
        return i_zero;
      }

      // The non-coplanar core on given (canonical) triangles. Returns the kind;
      // on point and segment, sets the generating edges of the start and end
      // along n_P x n_Q.
      IntersectionKind
      intersect_core(const Triangle3 &P,
                     const Triangle3 &Q,
                     int              sP[3],
                     int              sQ[3],
                     EdgeRef         &start,
                     EdgeRef         &end)
      {
        for (unsigned int i = 0; i < 3; ++i)
          sP[i] = orient3d(Q[0], Q[1], Q[2], P[i]);
        if (sP[0] == sP[1] && sP[1] == sP[2] && sP[0] != 0)
          return IntersectionKind::none;
        for (unsigned int i = 0; i < 3; ++i)
          sQ[i] = orient3d(P[0], P[1], P[2], Q[i]);
        if (sQ[0] == sQ[1] && sQ[1] == sQ[2])
          {
            if (sQ[0] != 0)
              return IntersectionKind::none;
            return coplanar_triangles_intersect(P, Q) ?
                     IntersectionKind::coplanar :
                     IntersectionKind::none;
          }
        if (sP[0] == 0 && sP[1] == 0 && sP[2] == 0)
          // Q is degenerate (P straddles no plane): P's plane is defined but
          // Q's is not.
          return coplanar_triangles_intersect(P, Q) ?
                   IntersectionKind::coplanar :
                   IntersectionKind::none;

        const unsigned int aP = alone_vertex(sP);
        const unsigned int aQ = alone_vertex(sQ);
        const EdgeRef      X{0, aP, (aP + 1) % 3}, Xp{0, aP, (aP + 2) % 3};
        const EdgeRef      Y{1, aQ, (aQ + 1) % 3}, Yp{1, aQ, (aQ + 2) % 3};
        // The chord of P along the line L = plane P ^ plane Q runs from X to X'
        // in direction +d = n_P x n_Q if P's alone vertex is below Q's plane;
        // the chord of Q runs from Y to Y' in direction +d if Q's alone vertex
        // is above P's plane.
        const EdgeRef lo1 = (sP[aP] < 0) ? X : Xp, hi1 = (sP[aP] < 0) ? Xp : X;
        const EdgeRef lo2 = (sQ[aQ] > 0) ? Y : Yp, hi2 = (sQ[aQ] > 0) ? Yp : Y;

        // sign of d . (X - Y) for X on edge e of P and Y on edge f of Q.
        const auto compare = [&](const EdgeRef &e, const EdgeRef &f) {
          return -orient3d(P[e.a], P[e.b], Q[f.a], Q[f.b]) *
                 sgn(sP[e.b] - sP[e.a]) * sgn(sQ[f.b] - sQ[f.a]);
        };

        const int c_lo1_hi2 = compare(lo1, hi2);
        if (c_lo1_hi2 > 0)
          return IntersectionKind::none;
        const int c_hi1_lo2 = compare(hi1, lo2);
        if (c_hi1_lo2 < 0)
          return IntersectionKind::none;
        const bool start_is_1 = compare(lo1, lo2) >= 0;
        const bool end_is_1   = compare(hi1, hi2) <= 0;
        start                 = start_is_1 ? lo1 : lo2;
        end                   = end_is_1 ? hi1 : hi2;

        bool single_point;
        if (start_is_1 && end_is_1)
          single_point = (sP[aP] == 0);
        else if (!start_is_1 && !end_is_1)
          single_point = (sQ[aQ] == 0);
        else if (start_is_1)
          single_point = (c_lo1_hi2 == 0);
        else
          single_point = (c_hi1_lo2 == 0);
        return single_point ? IntersectionKind::point :
                              IntersectionKind::segment;
      }

      // The point where edge (a, b) of E meets the plane of F; s are the exact
      // signs of E's vertices with respect to F's plane.
      inline Point3
      edge_plane_point(const Triangle3 &E,
                       const Triangle3 &F,
                       const int        s[3],
                       const unsigned   a,
                       const unsigned   b,
                       double          &t)
      {
        if (s[a] == 0)
          {
            t = 0.;
            return E[a];
          }
        if (s[b] == 0)
          {
            t = 1.;
            return E[b];
          }
        const Point3 n  = cross(minus(F[1], F[0]), minus(F[2], F[0]));
        const double da = dot(n, minus(E[a], F[0]));
        const double db = dot(n, minus(E[b], F[0]));
        t               = da / (da - db);
        if (!(t >= 0.)) // also catches NaN
          t = 0.;
        if (t > 1.)
          t = 1.;
        Point3 x;
        for (unsigned int k = 0; k < 3; ++k)
          x[k] = E[a][k] + t * (E[b][k] - E[a][k]);
        return x;
      }

      // Closed-triangle overlap in 2D; both triangles counterclockwise.
      bool
      segments_cross_2d(const Point2 &p,
                        const Point2 &q,
                        const Point2 &r,
                        const Point2 &s)
      {
        const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
        if (o1 * o2 > 0)
          return false;
        const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
        if (o3 * o4 > 0)
          return false;
        // All collinear: an overlap puts an end point of one on the other,
        // which the point-in-triangle tests find.
        return !(o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0);
      }

      bool
      inside_2d(const std::array<Point2, 3> &T, const Point2 &p)
      {
        return orient2d(T[0], T[1], p) >= 0 && orient2d(T[1], T[2], p) >= 0 &&
               orient2d(T[2], T[0], p) >= 0;
      }

      // Coplanar T0 and T1 projected onto the coordinate plane across the
      // axis along which T0's normal is largest (another if the projection
      // degenerates, which is checked exactly), each turned counterclockwise
      // there. Returns how T1 faced before it was turned: +1 as T0, -1
      // opposite; 0 if a triangle is degenerate.
      int
      project_coplanar_counterclockwise(const Triangle3       &T0,
                                        const Triangle3       &T1,
                                        std::array<Point2, 3> &A,
                                        std::array<Point2, 3> &B)
      {
        const Point3 n        = cross(minus(T0[1], T0[0]), minus(T0[2], T0[0]));
        unsigned int order[3] = {0, 1, 2};
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i + 1; j < 3; ++j)
            if (std::abs(n[order[j]]) > std::abs(n[order[i]]))
              std::swap(order[i], order[j]);
        for (const unsigned int axis : order)
          {
            const unsigned int i = (axis + 1) % 3, j = (axis + 2) % 3;
            for (unsigned int v = 0; v < 3; ++v)
              {
                A[v] = {{T0[v][i], T0[v][j]}};
                B[v] = {{T1[v][i], T1[v][j]}};
              }
            const int oA = orient2d(A[0], A[1], A[2]);
            if (oA == 0)
              continue;
            const int oB = orient2d(B[0], B[1], B[2]);
            if (oB == 0)
              return 0;
            if (oA < 0)
              std::swap(A[1], A[2]);
            if (oB < 0)
              std::swap(B[1], B[2]);
            return oA * oB;
          }
        return 0;
      }

      // Whether the line of an edge of the counterclockwise E has all of F
      // on its closed outer side: the interiors of two convex polygons are
      // disjoint if and only if such an edge of one of them exists.
      bool
      edge_separates_2d(const std::array<Point2, 3> &E,
                        const std::array<Point2, 3> &F)
      {
        for (unsigned int e = 0; e < 3; ++e)
          if (orient2d(E[e], E[(e + 1) % 3], F[0]) <= 0 &&
              orient2d(E[e], E[(e + 1) % 3], F[1]) <= 0 &&
              orient2d(E[e], E[(e + 1) % 3], F[2]) <= 0)
            return true;
        return false;
      }
    } // namespace



    bool
    coplanar_triangles_intersect(const Triangle3 &T0, const Triangle3 &T1)
    {
      std::array<Point2, 3> A, B;
      if (!project_coplanar_counterclockwise(T0, T1, A, B))
        return false;
      for (unsigned int v = 0; v < 3; ++v)
        if (inside_2d(A, B[v]) || inside_2d(B, A[v]))
          return true;
      for (unsigned int e = 0; e < 3; ++e)
        for (unsigned int f = 0; f < 3; ++f)
          if (segments_cross_2d(A[e], A[(e + 1) % 3], B[f], B[(f + 1) % 3]))
            return true;
      return false;
    }



    bool
    triangles_intersect(const Triangle3 &T0, const Triangle3 &T1)
    {
      int     sP[3], sQ[3];
      EdgeRef start, end;
      return intersect_core(T0, T1, sP, sQ, start, end) !=
             IntersectionKind::none;
    }



    bool
    triangles_cross(const Triangle3 &T0,
                    const Triangle3 &T1,
                    const bool       T1_bounds_a_body)
    {
      // s0: the side of T1's plane that each point of T0 lies on; s1: the
      // converse.
      int     s0[3], s1[3];
      EdgeRef start, end;
      switch (intersect_core(T0, T1, s0, s1, start, end))
        {
          case IntersectionKind::none:
          case IntersectionKind::point:
            return false;
          case IntersectionKind::coplanar:
            {
              if (!T1_bounds_a_body)
                return false;
              std::array<Point2, 3> A, B;
              return project_coplanar_counterclockwise(T0, T1, A, B) > 0 &&
                     !edge_separates_2d(A, B) && !edge_separates_2d(B, A);
            }
          case IntersectionKind::segment:
            break;
        }
      const auto outside = [](const int s[3]) {
        return s[0] >= 0 && s[1] >= 0 && s[2] >= 0;
      };
      const auto inside = [](const int s[3]) {
        return s[0] <= 0 && s[1] <= 0 && s[2] <= 0;
      };
      return !(outside(s1) || outside(s0) || (!T1_bounds_a_body && inside(s0)));
    }



    TriangleIntersection
    intersect_triangles(const Triangle3 &T0, const Triangle3 &T1)
    {
      // Canonical order: vertices sorted within each triangle, triangles
      // sorted.
      std::array<std::array<unsigned int, 3>, 2> perm = {
        {sorted_vertices(T0), sorted_vertices(T1)}};
      const Triangle3 *args[2] = {&T0, &T1};
      unsigned int     arg[2]  = {0, 1};
      {
        bool swap = false;
        for (unsigned int v = 0; v < 3; ++v)
          {
            const Point3 &x = T0[perm[0][v]], &y = T1[perm[1][v]];
            if (less_point(x, y))
              break;
            if (less_point(y, x))
              {
                swap = true;
                break;
              }
          }
        if (swap)
          {
            std::swap(arg[0], arg[1]);
            std::swap(perm[0], perm[1]);
          }
      }
      Triangle3 C[2];
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int v = 0; v < 3; ++v)
          C[k][v] = (*args[arg[k]])[perm[k][v]];

      TriangleIntersection result;
      int                  s[2][3];
      EdgeRef              ends[2];
      result.kind = intersect_core(C[0], C[1], s[0], s[1], ends[0], ends[1]);
      if (result.kind != IntersectionKind::point &&
          result.kind != IntersectionKind::segment)
        return result;

      for (unsigned int i = 0; i < 2; ++i)
        {
          const EdgeRef &e = ends[i];
          double         t;
          const Point3   x =
            edge_plane_point(C[e.k], C[1 - e.k], s[e.k], e.a, e.b, t);
          (i == 0 ? result.A : result.B) = x;
          SegmentEndPoint &src           = result.source[i];
          src.edge_triangle              = arg[e.k];
          src.edge                       = {{perm[e.k][e.a], perm[e.k][e.b]}};
          src.t                          = t;
        }
      if (result.kind == IntersectionKind::point)
        {
          result.B         = result.A;
          result.source[1] = result.source[0];
        }
      return result;
    }
  } // namespace contact
} // namespace estep
