// Points and closed surfaces (the deep-penetration check of ContactSystem):
// the distance to a triangle against a dense sampling of it, the solid angle of
// an octant, and the winding number and distance of points inside, outside and
// near a closed sphere.

#include <estep/contact/point_in_surface.h>

#include <gtest/gtest.h>

#include "test_meshes.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <random>

using namespace estep::contact;

TEST(PointInSurface, DistanceToTriangleMatchesSampling)
{
  std::mt19937_64                        rng(5);
  std::uniform_real_distribution<double> u(-1., 1.);
  const unsigned int                     n = 200; // samples per edge
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      Triangle3 t;
      Point3    p;
      for (auto &vertex : t)
        for (double &x : vertex)
          x = u(rng);
      for (double &x : p)
        x = 2. * u(rng);
      // The closest sample of a barycentric grid: never closer than the
      // exact distance, and farther by at most the grid's spacing.
      double sampled = std::numeric_limits<double>::infinity();
      for (unsigned int i = 0; i <= n; ++i)
        for (unsigned int j = 0; i + j <= n; ++j)
          {
            const double a = double(i) / n, b = double(j) / n, c = 1. - a - b;
            double       d2 = 0.;
            for (unsigned int k = 0; k < 3; ++k)
              {
                const double x = a * t[0][k] + b * t[1][k] + c * t[2][k];
                d2 += (x - p[k]) * (x - p[k]);
              }
            sampled = std::min(sampled, std::sqrt(d2));
          }
      double longest = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          const Point3 e = minus(t[(k + 1) % 3], t[k]);
          longest        = std::max(longest, std::sqrt(dot(e, e)));
        }
      const double exact = std::sqrt(squared_distance_to_triangle(p, t));
      EXPECT_LE(exact, sampled + 1e-12) << "trial " << trial;
      EXPECT_GE(exact, sampled - longest / n) << "trial " << trial;
    }
}

TEST(PointInSurface, SolidAngleOfAnOctant)
{
  const Triangle3 t = {{{{1., 0., 0.}}, {{0., 1., 0.}}, {{0., 0., 1.}}}};
  // Seen from the origin, behind the triangle's normal (1, 1, 1): +pi/2.
  EXPECT_NEAR(solid_angle({{0., 0., 0.}}, t), M_PI / 2., 1e-14);
  const Triangle3 flipped = {{t[0], t[2], t[1]}};
  EXPECT_NEAR(solid_angle({{0., 0., 0.}}, flipped), -M_PI / 2., 1e-14);
  // In the triangle's plane, outside it: 0.
  EXPECT_NEAR(solid_angle({{2., 0., -1.}}, t), 0., 1e-14);
}

TEST(PointInSurface, WindingNumberAndDistanceOfASphere)
{
  std::vector<double>          q;
  std::vector<TriangleIndices> triangles;
  estep_test::add_sphere(q, triangles, 0., 0., 0., 1., 12, 16);
  std::vector<unsigned int> all(triangles.size());
  std::iota(all.begin(), all.end(), 0u);

  // Inside: winding number 1, distance a little below 1 - |p| (the
  // polyhedron lies inside the sphere).
  const PointAndSurface inside =
    locate_point({{0.1, -0.2, 0.3}}, q.data(), triangles, all, 0.1);
  EXPECT_NEAR(inside.winding_number, 1., 1e-12);
  EXPECT_LT(inside.distance, 1. - std::sqrt(0.14));
  EXPECT_GT(inside.distance, 1. - std::sqrt(0.14) - 0.05);

  // Outside, beside and far: 0.
  for (const Point3 &p : {Point3{{1.5, 0., 0.}}, Point3{{0., 0., -7.}}})
    {
      const PointAndSurface outside =
        locate_point(p, q.data(), triangles, all, 0.1);
      EXPECT_NEAR(outside.winding_number, 0., 1e-12);
      EXPECT_GT(outside.distance, 0.4);
    }

  // Near the surface: the search stops at a triangle closer than `near`,
  // without a winding number.
  const PointAndSurface near =
    locate_point({{0., 0.97, 0.}}, q.data(), triangles, all, 0.1);
  EXPECT_LE(near.distance, 0.1);
  EXPECT_TRUE(std::isnan(near.winding_number));
}
