// LineTaylorForm: the enclosure of a quadratic is its exact range, a kink
// (slope offset) is held by the enclosure of a sum, the curvature is reported
// only without a kink, forms about different intervals do not add.

#include <estep/systems/line_taylor_form.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

TEST(LineTaylorForm, QuadraticAndKink)
{
  // f(s) = s^2 on [0, 1]: exact range from the form about 0.5.
  estep::LineTaylorForm square = estep::LineTaylorForm::about_centre_of(0., 1.);
  square.value                 = 0.25;
  square.slope                 = 1.;
  square.curvature             = {2., 2.};
  const auto e                 = square.enclosure();
  EXPECT_TRUE(square.bounds_curvature());
  EXPECT_EQ(e.curvature.lower, 2.);
  EXPECT_EQ(e.curvature.upper, 2.);
  // (up to the outward rounding of a few units of round-off)
  EXPECT_NEAR(e.value.lower, 0., 1e-14);
  EXPECT_NEAR(e.value.upper, 1., 1e-14);
  EXPECT_NEAR(e.derivative.lower, 0., 1e-14);
  EXPECT_NEAR(e.derivative.upper, 2., 1e-14);

  // f(s) = |s - 0.3| + s^2 (a kink: f' jumps by 2): W = [-2, 0] about 0.5.
  estep::LineTaylorForm kink = estep::LineTaylorForm::about_centre_of(0., 1.);
  kink.value                 = 0.2 + 0.25;
  kink.slope                 = 1. + 1.;
  kink.slope_offset          = {-2., 0.};
  estep::LineTaylorForm sum  = estep::LineTaylorForm::about_centre_of(0., 1.);
  sum += kink;
  sum.curvature = {2., 2.};
  const auto k  = sum.enclosure();
  // A kink: no curvature bound.
  EXPECT_FALSE(sum.bounds_curvature());
  EXPECT_FALSE(std::isfinite(k.curvature.lower));
  EXPECT_FALSE(std::isfinite(k.curvature.upper));
  for (unsigned int j = 0; j <= 100; ++j)
    {
      const double s = j / 100.;
      EXPECT_TRUE(k.value.contains(std::abs(s - 0.3) + s * s));
      EXPECT_TRUE(k.derivative.contains((s < 0.3 ? -1. : 1.) + 2. * s));
    }
  // Scaling keeps the form smooth: -s^2 is concave.
  const estep::LineTaylorForm negative = square.scaled(-1.);
  EXPECT_TRUE(negative.bounds_curvature());
  EXPECT_LT(negative.enclosure().curvature.upper, 0.);
  // Forms about different intervals do not add.
  EXPECT_THROW(sum += estep::LineTaylorForm::about_centre_of(0., 2.),
               std::logic_error);
}
