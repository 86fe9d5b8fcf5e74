// find_first_contact(): the first contact along a flight, and the rule for
// primitives that touch at the start.
#include <estep/contact/first_contact.h>

#include <gtest/gtest.h>

#include <initializer_list>
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
