// find_first_contact(): the first contact along a flight, and the rule for
// primitives that touch at the start.
#include <estep/contact/first_contact.h>

#include <gtest/gtest.h>

#include "test_meshes.h"

#include <algorithm>
#include <initializer_list>
#include <stdexcept>
#include <vector>

using namespace estep::contact;

namespace
{
  struct Point
  {
    double x, y, z;
  };

  /** Point-major coordinates of the points @p points. */
  std::vector<double>
  coordinates(std::initializer_list<Point> points)
  {
    std::vector<double> q;
    for (const Point &p : points)
      q.insert(q.end(), {p.x, p.y, p.z});
    return q;
  }

  // Triangle 0 (points 0-2) at rest in the plane y = 0 with an edge on the x
  // axis from x = 0 to 1; triangle 1 (points 3-5) in the plane x = 5, with an
  // edge on the line {x = 5, y = 0}, moving with velocity (-1, vy, 0). The two
  // edges lie on lines that meet at (5, 0, 0): along their common normal they
  // are at distance 0 although the segments are 4 apart.
  struct Scene
  {
    std::vector<TriangleIndices> triangles = {{{0, 1, 2}}, {{3, 4, 5}}};
    std::vector<double>          q         = coordinates({{0., 0., 0.},
                                                          {1., 0., 0.},
                                                          {0., 0., 3.},
                                                          {5., 0., 1.},
                                                          {5., 0., 2.},
                                                          {5., 1., 1.5}});
    std::vector<double>          v;

    explicit Scene(const double vy)
      : v(18, 0.)
    {
      for (unsigned int point = 3; point < 6; ++point)
        {
          v[3 * point]     = -1.;
          v[3 * point + 1] = vy;
        }
    }

    std::optional<FirstContact>
    first_contact(const double s_max) const
    {
      return find_first_contact(triangles, {}, q.data(), v.data(), 18, s_max);
    }
  };
} // namespace

TEST(FirstContact, DistantEdgesOnMeetingLinesAreNotTouching)
{
  // Moving towards y < 0, triangle 1 sweeps through triangle 0: the first
  // contact is its lower edge's meeting with the edge z = 3 (1 - x) of
  // triangle 0 at s = 13 / 2.95 = 4.407 (the CCD reports it no later).
  const auto hit = Scene(-0.1).first_contact(10.);
  ASSERT_TRUE(hit.has_value());
  EXPECT_GT(hit->s, 4.3);
  EXPECT_LE(hit->s, 13. / 2.95 + 1e-9);

  // Moving towards y > 0, it passes beside triangle 0 and never touches it.
  EXPECT_FALSE(Scene(0.1).first_contact(10.).has_value());
}

TEST(FirstContact, CoordinatesBeyondTheToleranceAreRefused)
{
  // The scene of the first test, moved by a distance: within 2^45 times the
  // tolerance the same contact is found; beyond it the search refuses rather
  // than subdivide to the iteration cap at every step.
  CcdSettings settings;
  for (const double shift : {0.9, 1.1})
    {
      Scene moved(-0.1);
      for (double &x : moved.q)
        x += shift * ccd_coordinate_limit(settings.tolerance);
      const auto search = [&] {
        return find_first_contact(moved.triangles,
                                  {},
                                  moved.q.data(),
                                  moved.v.data(),
                                  18,
                                  10.,
                                  settings);
      };
      if (shift < 1.)
        {
          const auto hit = search();
          ASSERT_TRUE(hit.has_value());
          EXPECT_GT(hit->s, 4.3);
          EXPECT_LE(hit->s, 13. / 2.95 + 1e-6);
        }
      else
        EXPECT_THROW(search(), std::runtime_error);
    }
}

TEST(FirstContact, TouchingPairsApproachOrSeparate)
{
  // A vertex of triangle 1 on the face of triangle 0 (at x = 0.2, z = 0.5),
  // triangle 1 otherwise on the side y > 0, which triangle 0 now faces (its
  // outward normal +y).
  Scene scene(0.);
  scene.triangles[0] = {{0, 2, 1}};
  scene.q            = coordinates({{0., 0., 0.},
                                    {1., 0., 0.},
                                    {0., 0., 3.},
                                    {0.2, 0., 0.5},
                                    {0.2, 1., 0.5},
                                    {0.4, 1., 1.}});
  for (const double vy : {-1., 1.})
    {
      for (unsigned int point = 3; point < 6; ++point)
        {
          scene.v[3 * point]     = 0.;
          scene.v[3 * point + 1] = vy;
        }
      const auto hit = scene.first_contact(1.);
      if (vy < 0.)
        {
          // Approaching: a contact now, with the normal of the face.
          ASSERT_TRUE(hit.has_value());
          EXPECT_EQ(hit->s, 0.);
          EXPECT_NEAR(std::abs(hit->normal[1]), 1., 1e-12);
        }
      else
        EXPECT_FALSE(hit.has_value()) << "separating, hit at s = " << hit->s;
    }
}

TEST(FirstContact, TouchingPairsApproachingWithinRoundOffAreHeld)
{
  // A vertex of triangle 1 on the face of triangle 0, everything moving
  // together at (0.3, 1, 0.7): the pair's rate is round-off, which no
  // reflection could change (the velocities' last bits are larger), so the
  // pair is held, not a contact now, even where the round-off is negative.
  // A real approach, the vertex slower by 1e-9 along the normal, is one.
  Scene scene(0.);
  scene.triangles[0]                                  = {{0, 2, 1}};
  const std::array<unsigned int, 4> points            = {{3, 0, 2, 1}};
  unsigned int                      negative_roundoff = 0;
  for (unsigned int i = 1; i < 40; ++i)
    {
      const double x = 0.0123 * i, z = 0.0371 * i;
      scene.q = coordinates({{0., 0., 0.},
                             {1., 0., 0.},
                             {0., 0., 3.},
                             {x, 0., z},
                             {x, 1., z},
                             {x + 0.2, 1., z + 0.5}});
      for (unsigned int point = 0; point < 6; ++point)
        {
          scene.v[3 * point]     = 0.3;
          scene.v[3 * point + 1] = 1.;
          scene.v[3 * point + 2] = 0.7;
        }
      // The rate as the search computes it.
      const FirstContact c =
        contact_normal(points, false, scene.q.data(), {{0., 1., 0.}});
      double rate = 0.;
      for (unsigned int k = 0; k < 4; ++k)
        for (unsigned int d = 0; d < 3; ++d)
          rate += c.weights[k] * c.normal[d] * scene.v[3 * points[k] + d];
      negative_roundoff += rate < 0.;
      const auto held = scene.first_contact(1.);
      EXPECT_FALSE(held.has_value()) << "x = " << x << ", rate " << rate;

      scene.v[3 * 3 + 1] = 1. - 1e-9;
      const auto hit     = scene.first_contact(1.);
      ASSERT_TRUE(hit.has_value()) << "x = " << x;
      EXPECT_EQ(hit->s, 0.);
      EXPECT_EQ(hit->points, points);
    }
  EXPECT_GT(negative_roundoff, 0u);
}

TEST(FirstContact, TouchingContactsIncludePairsAtTheTouchingDistance)
{
  // Triangle 1 parallel to triangle 0, 3 tolerances above it: farther than
  // the tolerance that enlarges the boxes of the search's broad phase on
  // each side, within the touching distance 2 sqrt(3) tolerance. Its three
  // vertices touch triangle 0's face; an approach is a contact now, and its
  // pair is among the touching ones.
  const CcdSettings               settings;
  const double                    gap       = 3. * settings.tolerance;
  std::vector<TriangleIndices>    triangles = {{{0, 2, 1}}, {{3, 4, 5}}};
  const std::vector<double>       q         = coordinates({{0., 0., 0.},
                                                           {1., 0., 0.},
                                                           {0., 0., 3.},
                                                           {0.1, gap, 0.1},
                                                           {0.1, gap, 0.6},
                                                           {0.4, gap, 0.3}});
  BoundingVolumeHierarchy         tree(triangles, {0u, 1u});
  const std::vector<FirstContact> touching =
    touching_contacts(tree, q.data(), q.size(), settings);
  unsigned int vertices_on_the_face = 0;
  for (const FirstContact &c : touching)
    vertices_on_the_face += !c.edge_edge && c.points[0] >= 3;
  EXPECT_EQ(vertices_on_the_face, 3u);

  std::vector<double> v(q.size(), 0.);
  for (unsigned int point = 3; point < 6; ++point)
    v[3 * point + 1] = -1.;
  const auto hit =
    find_first_contact(tree, q.data(), v.data(), q.size(), 1., settings);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->s, 0.);
  EXPECT_TRUE(
    std::any_of(touching.begin(), touching.end(), [&](const FirstContact &c) {
      return c.points == hit->points && c.edge_edge == hit->edge_edge;
    }));
}

TEST(FirstContact, EdgeStandingOnAnEdgeEndOnHasTheNormalOfItsEnd)
{
  // A flat floor of two triangles (points 0-3, z = 0) that share the diagonal
  // edge 0-2 from (-1, -1) to (1, 1), and a body triangle (points 4-6) whose
  // edge 4-5 stands on that diagonal end-on: point 4 at (0, 0, 1e-6), within
  // the collision tolerance, point 5 straight above it. The lines of the two
  // edges meet at the origin, just beyond point 4: their common normal is
  // horizontal, across the diagonal, while the edges come closest at point 4,
  // straight above it. Sliding along the floor, the body neither approaches
  // nor leaves it: no contact. (With the lines' normal, the pair was touching
  // and approaching at a rate of 1 / sqrt(2) along one of the two directions,
  // reported at s = 0: a box resting on a floor of two triangles got a
  // sideways kick at its first contact.)
  const std::vector<TriangleIndices> triangles = {{{0, 1, 2}},
                                                  {{0, 2, 3}},
                                                  {{4, 5, 6}}};
  const std::vector<unsigned int>    groups    = {0, 0, 1};
  const std::vector<double>          q         = coordinates({{-1., -1., 0.},
                                                              {1., -1., 0.},
                                                              {1., 1., 0.},
                                                              {-1., 1., 0.},
                                                              {0., 0., 1e-6},
                                                              {0., 0., 0.1},
                                                              {-0.1, 0.05, 0.1}});
  for (const Point3 &velocity : {Point3{{1., 0., 0.}}, Point3{{0., 1., 0.}}})
    {
      std::vector<double> v(q.size(), 0.);
      for (unsigned int point = 4; point < 7; ++point)
        for (unsigned int c = 0; c < 3; ++c)
          v[3 * point + c] = velocity[c];
      const auto hit = find_first_contact(
        triangles, groups, q.data(), v.data(), q.size(), 0.1);
      EXPECT_FALSE(hit.has_value())
        << "sliding along (" << velocity[0] << ", " << velocity[1]
        << ", 0): hit at s = " << hit->s << ", normal (" << hit->normal[0]
        << ", " << hit->normal[1] << ", " << hit->normal[2] << ")";
    }
  // The pair's normal is that of its closest points, point 4 and its foot on
  // the diagonal (the middle of the diagonal), with the weights there.
  const FirstContact c =
    contact_normal({{4, 5, 0, 2}}, true, q.data(), {{0., 0., 1.}});
  EXPECT_NEAR(c.normal[2], 1., 1e-12);
  EXPECT_EQ(c.weights[0], 1.);
  EXPECT_EQ(c.weights[1], 0.);
  EXPECT_NEAR(c.weights[2], -0.5, 1e-12);
  EXPECT_NEAR(c.weights[3], -0.5, 1e-12);
}

TEST(FirstContact, KeptTreeGivesTheResultOfAFreshOne)
{
  // Two spheres (a group each) approach, spinning, over 40 flights from
  // configurations that drift flight after flight: the overload that keeps
  // its tree, refitted from earlier flights' configurations, finds the same
  // contact as a tree built for each flight, to the last bit (point indices,
  // flight parameter, weights, normal), with contacts found on most of them.
  std::vector<double>          q;
  std::vector<TriangleIndices> triangles, second;
  estep_test::add_sphere(q, triangles, 0., 0., 0., 1., 16, 16);
  const unsigned int first_size = triangles.size();
  estep_test::add_sphere(q, second, 2.3, 0.1, 0.05, 1., 16, 16);
  triangles.insert(triangles.end(), second.begin(), second.end());
  std::vector<unsigned int> groups(triangles.size(), 0u);
  std::fill(groups.begin() + first_size, groups.end(), 1u);
  const std::size_t n = q.size(), half = n / 2;
  // Ball 2 moves towards ball 1 and spins about the y axis through its
  // centre; ball 1 spins about the z axis.
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; i += 3)
    {
      const bool   ball_two = i >= half;
      const double cx = ball_two ? 2.3 : 0., cz = ball_two ? 0.05 : 0.;
      const double x = q[i] - cx, y = q[i + 1], z = q[i + 2] - cz;
      if (ball_two)
        {
          v[i]     = -1. + 0.8 * z;
          v[i + 1] = 0.;
          v[i + 2] = -0.8 * x;
        }
      else
        {
          v[i]     = -0.5 * y;
          v[i + 1] = 0.5 * x;
          v[i + 2] = 0.;
        }
    }
  BoundingVolumeHierarchy kept(triangles, groups);
  unsigned int            contacts = 0;
  for (unsigned int flight = 0; flight < 40; ++flight)
    {
      const double        t = 0.01 * flight;
      std::vector<double> x(n);
      for (std::size_t i = 0; i < n; ++i)
        x[i] = q[i] + t * v[i];
      const double s_max = 0.5;
      const auto   fresh =
        find_first_contact(triangles, groups, x.data(), v.data(), n, s_max);
      const auto again = find_first_contact(kept, x.data(), v.data(), n, s_max);
      ASSERT_EQ(fresh.has_value(), again.has_value()) << "flight " << flight;
      if (!fresh)
        continue;
      ++contacts;
      EXPECT_EQ(fresh->s, again->s) << "flight " << flight;
      EXPECT_EQ(fresh->edge_edge, again->edge_edge) << "flight " << flight;
      EXPECT_EQ(fresh->points, again->points) << "flight " << flight;
      EXPECT_EQ(fresh->weights, again->weights) << "flight " << flight;
      EXPECT_EQ(fresh->normal, again->normal) << "flight " << flight;
    }
  EXPECT_GT(contacts, 20u);
}
