// orient2d / orient3d against CGAL's exact predicates, on random and
// near-degenerate inputs.

#include <estep/contact/predicates.h>

#include <gtest/gtest.h>

#include "cgal_oracle.h"

using namespace estep::contact;
using estep_test::CPoint;
using estep_test::Kernel;

namespace
{
  int
  cgal_sign(const CGAL::Orientation o)
  {
    return o == CGAL::POSITIVE ? 1 : (o == CGAL::NEGATIVE ? -1 : 0);
  }

  Point3
  random_point(std::mt19937_64 &rng, const double scale, const double offset)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    return {{offset + scale * u(rng),
             offset + scale * u(rng),
             offset + scale * u(rng)}};
  }
} // namespace

TEST(Orient3d, AgreesWithCgalOnNearlyCoplanarPoints)
{
  std::mt19937_64                        rng(1);
  std::uniform_real_distribution<double> u(0., 1.);
  unsigned int                           n_zero = 0;
  const unsigned int                     n = estep_test::size(20000, 1000000);
  for (unsigned int i = 0; i < n; ++i)
    {
      const double offset = (i % 3 == 0) ? 0. : (i % 3 == 1 ? 1e3 : 1e7);
      const double scale  = (i % 5 == 0) ? 1e-6 : 1.;
      const Point3 a      = random_point(rng, scale, offset),
                   b      = random_point(rng, scale, offset),
                   c      = random_point(rng, scale, offset);
      // d: an affine combination of a, b, c rounded to doubles, so nearly (or
      // exactly) coplanar.
      const double s = u(rng), t = u(rng) * (1. - s);
      Point3       d;
      for (unsigned int k = 0; k < 3; ++k)
        d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
      if (i % 7 == 0)
        d = b; // exactly degenerate
      const int expected =
        cgal_sign(CGAL::orientation(CPoint(a[0], a[1], a[2]),
                                    CPoint(b[0], b[1], b[2]),
                                    CPoint(c[0], c[1], c[2]),
                                    CPoint(d[0], d[1], d[2])));
      n_zero += (expected == 0);
      ASSERT_EQ(orient3d(a, b, c, d), expected) << "i = " << i;
      ASSERT_EQ(orient3d_exact(a, b, c, d), expected) << "i = " << i;
      ASSERT_EQ(orient3d(b, a, c, d), -expected);
    }
  EXPECT_GT(n_zero, n / 10);
}

TEST(Orient2d, AgreesWithCgalOnNearlyCollinearPoints)
{
  using P2 = Kernel::Point_2;
  std::mt19937_64                        rng(2);
  std::uniform_real_distribution<double> u(-1., 1.);
  const unsigned int                     n = estep_test::size(20000, 1000000);
  for (unsigned int i = 0; i < n; ++i)
    {
      const double offset = (i % 2) ? 0. : 1e5;
      const Point2 a      = {{offset + u(rng), offset + u(rng)}};
      const Point2 b      = {{offset + u(rng), offset + u(rng)}};
      const double s      = u(rng);
      Point2       c = {{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])}};
      if (i % 5 == 0)
        c = a;
      const int expected = cgal_sign(
        CGAL::orientation(P2(a[0], a[1]), P2(b[0], b[1]), P2(c[0], c[1])));
      ASSERT_EQ(orient2d(a, b, c), expected) << "i = " << i;
      ASSERT_EQ(orient2d_exact(a, b, c), expected);
    }
}

TEST(Orient3d, TinyDifferencesAtLargeOffset)
{
  // Differences of one unit in the last place at 1e8: the filter must defer to
  // the exact path.
  const double x = 1e8, e = std::nextafter(x, 2e8) - x;
  const Point3 a = {{x, x, x}}, b = {{x + e, x, x}}, c = {{x, x + e, x}};
  EXPECT_EQ(orient3d(a, b, c, {{x, x, x + e}}), 1);
  EXPECT_EQ(orient3d(a, b, c, {{x, x, x - e}}), -1);
  EXPECT_EQ(orient3d(a, b, c, {{x + 3 * e, x + 5 * e, x}}), 0);
}
