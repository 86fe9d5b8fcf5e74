// Triangle-triangle intersection against CGAL's exact kernel: yes/no, kind, end
// points, and invariance under reordering of vertices and triangles.

#include <estep/contact/triangle_intersection.h>

#include <gtest/gtest.h>

#include "cgal_oracle.h"

#include <algorithm>
#include <cmath>

using namespace estep::contact;
using namespace estep_test;

namespace
{
  constexpr double u_round = 1.1102230246251565e-16;

  bool
  degenerate(const Triangle3 &T)
  {
    return to_cgal(T).is_degenerate();
  }

  Triangle3
  random_triangle(std::mt19937_64 &rng,
                  const double     scale,
                  const Point3    &offset)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    Triangle3                              T;
    for (auto &p : T)
      for (unsigned int k = 0; k < 3; ++k)
        p[k] = offset[k] + scale * u(rng);
    return T;
  }

  /** CGAL's kind, mapped to ours: coplanar if the two planes coincide. */
  IntersectionKind
  cgal_kind(const Triangle3 &T0, const Triangle3 &T1)
  {
    const CTriangle a = to_cgal(T0), b = to_cgal(T1);
    if (!CGAL::do_intersect(a, b))
      return IntersectionKind::none;
    bool coplanar = true;
    for (unsigned int v = 0; v < 3; ++v)
      coplanar = coplanar && CGAL::coplanar(a[0], a[1], a[2], b[v]);
    if (coplanar)
      return IntersectionKind::coplanar;
    const auto result = CGAL::intersection(a, b);
    if (!result)
      return IntersectionKind::none; // should not happen
    if (boost::get<CPoint>(&*result))
      return IntersectionKind::point;
    if (boost::get<CSegment>(&*result))
      return IntersectionKind::segment;
    return IntersectionKind::coplanar;
  }

  std::string
  describe(const Triangle3 &T0, const Triangle3 &T1)
  {
    std::ostringstream s;
    s.precision(17);
    for (const auto *T : {&T0, &T1})
      for (const auto &p : *T)
        s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ") ";
    return s.str();
  }

  /** The physical description of an end point's source: edge vertices and face
   * vertices. */
  std::array<Point3, 2>
  source_edge(const SegmentEndPoint &s,
              const Triangle3       &T0,
              const Triangle3       &T1)
  {
    const Triangle3 &E = s.edge_triangle == 0 ? T0 : T1;
    return {{E[s.edge[0]], E[s.edge[1]]}};
  }

  /** Check that every reordering gives the same result. */
  void
  check_invariance(const Triangle3 &T0, const Triangle3 &T1)
  {
    const TriangleIntersection               ref = intersect_triangles(T0, T1);
    std::array<unsigned int, 3>              p   = {{0, 1, 2}};
    std::vector<std::array<unsigned int, 3>> perms;
    do
      perms.push_back(p);
    while (std::next_permutation(p.begin(), p.end()));
    for (const auto &p0 : perms)
      for (const auto &p1 : perms)
        for (const bool swap : {false, true})
          {
            Triangle3 A, B;
            for (unsigned int v = 0; v < 3; ++v)
              {
                A[v] = T0[p0[v]];
                B[v] = T1[p1[v]];
              }
            if (swap)
              std::swap(A, B);
            const TriangleIntersection r = intersect_triangles(A, B);
            ASSERT_EQ(r.kind, ref.kind) << describe(T0, T1);
            if (r.kind == IntersectionKind::point ||
                r.kind == IntersectionKind::segment)
              {
                ASSERT_EQ(r.A, ref.A) << describe(T0, T1);
                ASSERT_EQ(r.B, ref.B) << describe(T0, T1);
                for (unsigned int i = 0; i < 2; ++i)
                  {
                    ASSERT_EQ(source_edge(r.source[i], A, B),
                              source_edge(ref.source[i], T0, T1));
                    ASSERT_EQ(r.source[i].t, ref.source[i].t);
                    // The face is the other argument: same physical triangle.
                    const bool face_is_T1_ref =
                      ref.source[i].edge_triangle == 0;
                    const bool face_is_T1 =
                      (r.source[i].edge_triangle == 0) != swap;
                    ASSERT_EQ(face_is_T1, face_is_T1_ref);
                  }
              }
          }
  }

  double
  distance(const Point3 &a, const Point3 &b)
  {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) +
                     (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
  }

  /**
   * Error bound for an end point: u * (size of coordinates) / sin(angle between
   * the generating edge and the face's plane), times a safety factor.
   */
  double
  end_point_tolerance(const SegmentEndPoint &s,
                      const Triangle3       &T0,
                      const Triangle3       &T1)
  {
    const Triangle3 &E = s.edge_triangle == 0 ? T0 : T1;
    const Triangle3 &F = s.edge_triangle == 0 ? T1 : T0;
    double           L = 0.;
    for (const auto *T : {&T0, &T1})
      for (const auto &p : *T)
        for (const double x : p)
          L = std::max(L, std::abs(x));
    Point3 e, f1, f2;
    for (unsigned int k = 0; k < 3; ++k)
      {
        e[k]  = E[s.edge[1]][k] - E[s.edge[0]][k];
        f1[k] = F[1][k] - F[0][k];
        f2[k] = F[2][k] - F[0][k];
      }
    const Point3 n  = {{f1[1] * f2[2] - f1[2] * f2[1],
                        f1[2] * f2[0] - f1[0] * f2[2],
                        f1[0] * f2[1] - f1[1] * f2[0]}};
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double ee = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const double sine =
      std::abs(n[0] * e[0] + n[1] * e[1] + n[2] * e[2]) / (nn * ee);
    // The face's normal itself is computed from differences of size |f|:
    // relative error u L / |f| in the normal, amplified by 1/sine.
    const double f =
      std::min(std::sqrt(f1[0] * f1[0] + f1[1] * f1[1] + f1[2] * f1[2]),
               std::sqrt(f2[0] * f2[0] + f2[1] * f2[1] + f2[2] * f2[2]));
    return 64. * u_round * (L + ee * L / f) / sine;
  }
} // namespace

TEST(TriangleIntersection, RandomPairsAgreeWithCgal)
{
  std::mt19937_64                        rng(11);
  std::uniform_real_distribution<double> u(-1., 1.);
  const unsigned int                     n          = size(20000, 1000000);
  unsigned int                           n_disagree = 0, n_yes = 0, n_kind = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      // Scales from 1e-4 to 1e4, offsets up to 1e6.
      const double    scale  = std::pow(10., (i % 9) - 4.);
      const double    off    = (i % 4 == 0) ? 0. : std::pow(10., i % 7) * scale;
      const Point3    offset = {{off * u(rng), off * u(rng), off * u(rng)}};
      const Triangle3 T0     = random_triangle(rng, scale, offset);
      Triangle3       T1     = random_triangle(rng, scale, offset);
      if (degenerate(T0) || degenerate(T1))
        continue;
      const bool ours   = triangles_intersect(T0, T1);
      const bool theirs = CGAL::do_intersect(to_cgal(T0), to_cgal(T1));
      n_disagree += (ours != theirs);
      n_yes += theirs;
      EXPECT_EQ(ours, theirs) << describe(T0, T1);
      if (theirs)
        {
          const TriangleIntersection r = intersect_triangles(T0, T1);
          n_kind += (r.kind != cgal_kind(T0, T1));
        }
    }
  EXPECT_EQ(n_disagree, 0u);
  EXPECT_EQ(n_kind, 0u);
  EXPECT_GT(n_yes, n / 20);
  std::cout << "random pairs: " << n << ", intersecting: " << n_yes
            << ", yes/no disagreements: " << n_disagree
            << ", kind disagreements: " << n_kind << std::endl;
}

TEST(TriangleIntersection, SegmentEndPointsAgreeWithCgal)
{
  std::mt19937_64                        rng(12);
  std::uniform_real_distribution<double> u(-1., 1.);
  const unsigned int                     n         = size(5000, 200000);
  unsigned int                           n_checked = 0, n_bad = 0;
  double                                 worst = 0.;
  while (n_checked < n)
    {
      const double    scale  = std::pow(10., (n_checked % 7) - 3.);
      const double    off    = (n_checked % 3 == 0) ? 0. : 1e3 * scale;
      const Point3    offset = {{off * u(rng), off * u(rng), off * u(rng)}};
      const Triangle3 T0     = random_triangle(rng, scale, offset);
      const Triangle3 T1     = random_triangle(rng, scale, offset);
      if (degenerate(T0) || degenerate(T1))
        continue;
      const TriangleIntersection r = intersect_triangles(T0, T1);
      if (r.kind != IntersectionKind::segment)
        continue;
      const auto result = CGAL::intersection(to_cgal(T0), to_cgal(T1));
      ASSERT_TRUE(result);
      const CSegment *s = boost::get<CSegment>(&*result);
      ASSERT_NE(s, nullptr) << describe(T0, T1);
      const Point3 P = to_double(s->source()), Q = to_double(s->target());
      const double tA = end_point_tolerance(r.source[0], T0, T1);
      const double tB = end_point_tolerance(r.source[1], T0, T1);
      const double e1 = std::max(distance(r.A, P) / tA, distance(r.B, Q) / tB);
      const double e2 = std::max(distance(r.A, Q) / tA, distance(r.B, P) / tB);
      const double e  = std::min(e1, e2);
      worst           = std::max(worst, e);
      if (e > 1.)
        {
          ++n_bad;
          ADD_FAILURE() << describe(T0, T1) << " error/tolerance " << e << " A "
                        << r.A[0] << "," << r.A[1] << "," << r.A[2] << " B "
                        << r.B[0] << "," << r.B[1] << "," << r.B[2] << " P "
                        << P[0] << "," << P[1] << "," << P[2] << " Q " << Q[0]
                        << "," << Q[1] << "," << Q[2] << " tA " << tA << " tB "
                        << tB << " src " << r.source[0].edge_triangle
                        << r.source[0].edge[0] << r.source[0].edge[1] << " "
                        << r.source[1].edge_triangle << r.source[1].edge[0]
                        << r.source[1].edge[1];
        }
      ++n_checked;
    }
  EXPECT_EQ(n_bad, 0u);
  std::cout << "segments checked: " << n_checked
            << ", outside tolerance: " << n_bad
            << ", worst error/tolerance: " << worst << std::endl;
}

namespace
{
  /** Degenerate configurations on a small integer grid (scaled and offset
   * exactly). */
  std::pair<Triangle3, Triangle3>
  degenerate_pair(std::mt19937_64 &rng, const unsigned int i)
  {
    std::uniform_int_distribution<int> g(0, 3);
    const double                       h   = (i % 2) ? 0.25 : 1024.;
    const double                       off = (i % 3) ? 0. : 65536.;
    auto                               pt  = [&]() {
      return Point3{{off + h * g(rng), off + h * g(rng), off + h * g(rng)}};
    };
    Triangle3 T0 = {{pt(), pt(), pt()}}, T1 = {{pt(), pt(), pt()}};
    switch (i % 6)
      {
        case 0: // grid-snapped, often coplanar or touching
          break;
        case 1: // coplanar: all on a grid plane z = const
          for (auto &p : T1)
            p[2] = T0[0][2];
          for (auto &p : T0)
            p[2] = T0[0][2];
          break;
        case 2: // shared vertex
          T1[g(rng) % 3] = T0[g(rng) % 3];
          break;
        case 3: // shared edge
          T1[0] = T0[0];
          T1[1] = T0[1];
          break;
        case 4: // a vertex of T1 on the plane of T0 (exact: a grid combination)
          for (unsigned int k = 0; k < 3; ++k)
            T1[0][k] =
              T0[0][k] + (T0[1][k] - T0[0][k]) - (T0[2][k] - T0[0][k]) * 0.5;
          break;
        case 5: // a vertex rounded onto the other plane (random combination,
                // rounded)
          {
            std::uniform_real_distribution<double> u(0., 1.);
            const double a = u(rng), b = u(rng) * (1. - a);
            for (unsigned int k = 0; k < 3; ++k)
              T1[0][k] = T0[0][k] + a * (T0[1][k] - T0[0][k]) +
                         b * (T0[2][k] - T0[0][k]);
            break;
          }
      }
    return {T0, T1};
  }
} // namespace

TEST(TriangleIntersection, DegeneratePairsAgreeWithCgalInKind)
{
  std::mt19937_64             rng(13);
  const unsigned int          n         = size(10000, 100000);
  unsigned int                n_checked = 0, n_bad = 0;
  std::array<unsigned int, 4> counts = {{0, 0, 0, 0}};
  for (unsigned int i = 0; n_checked < n; ++i)
    {
      const auto [T0, T1] = degenerate_pair(rng, i);
      if (degenerate(T0) || degenerate(T1))
        continue;
      const IntersectionKind expected = cgal_kind(T0, T1);
      const IntersectionKind ours     = intersect_triangles(T0, T1).kind;
      ++counts[static_cast<unsigned int>(expected)];
      if (ours != expected)
        {
          ++n_bad;
          ADD_FAILURE() << describe(T0, T1) << " ours "
                        << static_cast<int>(ours) << " CGAL "
                        << static_cast<int>(expected);
        }
      ASSERT_EQ(triangles_intersect(T0, T1),
                expected != IntersectionKind::none);
      ++n_checked;
    }
  EXPECT_EQ(n_bad, 0u);
  // The generator must exercise every kind.
  for (const unsigned int c : counts)
    EXPECT_GT(c, n / 100);
  std::cout << "degenerate pairs: " << n_checked << " (none " << counts[0]
            << ", point " << counts[1] << ", segment " << counts[2]
            << ", coplanar " << counts[3] << "), kind disagreements: " << n_bad
            << std::endl;
}

TEST(TriangleIntersection, InvariantUnderReordering)
{
  std::mt19937_64    rng(14);
  const unsigned int n              = size(300, 5000);
  unsigned int       n_intersecting = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      std::uniform_real_distribution<double> u(-1., 1.);
      Triangle3                              T0, T1;
      if (i % 2)
        std::tie(T0, T1) = degenerate_pair(rng, i / 2);
      else
        {
          T0 = random_triangle(rng, 1., {{0., 0., 0.}});
          T1 = random_triangle(rng, 1., {{0., 0., 0.}});
        }
      n_intersecting +=
        (intersect_triangles(T0, T1).kind != IntersectionKind::none);
      check_invariance(T0, T1);
      if (HasFatalFailure())
        return;
    }
  EXPECT_GT(n_intersecting, n / 10);
}

TEST(TriangleIntersection, KnownConfigurations)
{
  // A vertex touching the inside of a face: a point.
  const Triangle3      F = {{{{0., 0., 0.}}, {{4., 0., 0.}}, {{0., 4., 0.}}}};
  const Triangle3      V = {{{{1., 1., 0.}}, {{1., 1., 3.}}, {{2., 1., 3.}}}};
  TriangleIntersection r = intersect_triangles(F, V);
  EXPECT_EQ(r.kind, IntersectionKind::point);
  EXPECT_EQ(r.A, (Point3{{1., 1., 0.}}));
  // A triangle piercing another: segment from (1,1,0) to (1,2,0).
  const Triangle3 G = {{{{1., 1., -1.}}, {{1., 1., 1.}}, {{1., 3., -1.}}}};
  r                 = intersect_triangles(F, G);
  ASSERT_EQ(r.kind, IntersectionKind::segment);
  const Point3 a = {{1., 1., 0.}}, b = {{1., 2., 0.}};
  EXPECT_TRUE((r.A == a && r.B == b) || (r.A == b && r.B == a));
  // Coplanar overlap and coplanar disjoint.
  const Triangle3 H = {{{{1., 1., 0.}}, {{5., 1., 0.}}, {{1., 5., 0.}}}};
  EXPECT_EQ(intersect_triangles(F, H).kind, IntersectionKind::coplanar);
  const Triangle3 K = {{{{5., 5., 0.}}, {{9., 5., 0.}}, {{5., 9., 0.}}}};
  EXPECT_EQ(intersect_triangles(F, K).kind, IntersectionKind::none);
  // Degenerate triangle: none.
  const Triangle3 D = {{{{0., 0., 0.}}, {{1., 1., 1.}}, {{2., 2., 2.}}}};
  EXPECT_EQ(intersect_triangles(F, D).kind, IntersectionKind::none);
}

// Crossing against touching (triangles_cross()): the floor F bounds a body
// below z = 0 (its normal points up); the other triangles bound a body above
// it where they touch, and reach into the floor's body where they cross.
TEST(TriangleIntersection, CrossingAgainstTouching)
{
  const Triangle3 F = {{{{0., 0., 0.}}, {{4., 0., 0.}}, {{0., 4., 0.}}}};
  struct Case
  {
    const char *what;
    Triangle3   T;
    bool        crosses_body, crosses_surface;
  };
  const std::vector<Case> cases = {
    {"a flush face, facing down",
     {{{{1., 1., 0.}}, {{1., 3., 0.}}, {{3., 1., 0.}}}},
     false,
     false},
    {"a coplanar face facing up, overlapping",
     {{{{1., 1., 0.}}, {{3., 1., 0.}}, {{1., 3., 0.}}}},
     true,
     false},
    {"a coplanar face facing up, overlapping beyond an edge",
     {{{{1., 1., 0.}}, {{5., 1., 0.}}, {{1., 5., 0.}}}},
     true,
     false},
    {"a coplanar face facing up beside it, sharing an edge",
     {{{{4., 0., 0.}}, {{4., 4., 0.}}, {{0., 4., 0.}}}},
     false,
     false},
    {"a vertex on the face from above",
     {{{{1., 1., 0.}}, {{1., 1., 3.}}, {{2., 1., 3.}}}},
     false,
     false},
    {"a vertex through the face",
     {{{{1., 1., -0.1}}, {{1., 1., 3.}}, {{2., 1., 3.}}}},
     true,
     true},
    {"an edge on the face, the triangle standing on it",
     {{{{1., 1., 0.}}, {{2., 1., 0.}}, {{1., 1., 2.}}}},
     false,
     false},
    {"an edge on the face, the triangle hanging below it",
     {{{{1., 1., 0.}}, {{2., 1., 0.}}, {{1., 1., -2.}}}},
     true,
     false},
    {"an edge across the face's edge, a single point",
     {{{{2., -1., -1.}}, {{2., 1., 1.}}, {{3., 0., 3.}}}},
     false,
     false},
    {"a triangle piercing the face",
     {{{{1., 1., -1.}}, {{1., 1., 1.}}, {{1., 3., -1.}}}},
     true,
     true},
    {"a triangle apart",
     {{{{5., 5., 1.}}, {{9., 5., 1.}}, {{5., 9., 1.}}}},
     false,
     false}};
  for (const Case &c : cases)
    {
      EXPECT_EQ(triangles_cross(c.T, F, true), c.crosses_body) << c.what;
      EXPECT_EQ(triangles_cross(F, c.T, true), c.crosses_body)
        << c.what << " (the arguments swapped)";
      EXPECT_EQ(triangles_cross(c.T, F, false), c.crosses_surface)
        << c.what << " (the floor a surface)";
    }
  // A body's face flush under a surface's face, the surface either way up.
  const Triangle3 F_down = {{{{0., 0., 0.}}, {{0., 4., 0.}}, {{4., 0., 0.}}}};
  const Triangle3 below  = {{{{1., 1., 0.}}, {{3., 1., 0.}}, {{1., 3., 0.}}}};
  EXPECT_FALSE(triangles_cross(below, F, false));
  EXPECT_FALSE(triangles_cross(below, F_down, false));
  EXPECT_TRUE(triangles_cross(below, F, true));
  EXPECT_FALSE(triangles_cross(below, F_down, true));
}

// In general position (no point on another triangle's plane), intersecting
// triangles always cross: touching takes a point on a plane.
TEST(TriangleIntersection, IntersectingInGeneralPositionCross)
{
  std::mt19937_64    rng(5);
  const unsigned int n           = size(20000, 200000);
  unsigned int       n_intersect = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      const Triangle3 T0        = random_triangle(rng, 1., {{0., 0., 0.}});
      const Triangle3 T1        = random_triangle(rng, 1., {{0., 0., 0.}});
      const bool      intersect = triangles_intersect(T0, T1);
      n_intersect += intersect;
      EXPECT_EQ(triangles_cross(T0, T1, true), intersect) << describe(T0, T1);
      EXPECT_EQ(triangles_cross(T0, T1, false), intersect) << describe(T0, T1);
    }
  EXPECT_GT(n_intersect, n / 20);
}
