// Rigid half-space obstacles (HalfSpaceObstacles): the obstacle contacts of
// the impenetrable mode (the rule at s = 0, conservative in floating point,
// combined with the base's events), the penalty mode's gradient, Hessian and
// flight enclosures, and an elastic cube bouncing on a floor and a tilted
// plane under energy-stepping in both modes.

#include <deal.II/grid/tria.h>
#include <deal.II/lac/sparse_matrix.h>

#include <estep/composite/contact_system.h>
#include <estep/composite/half_space_obstacles.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>

#include <gtest/gtest.h>

#include "../terrace_audit.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <random>

using estep::HalfSpace;
using estep::HalfSpaceObstacles;
using estep::Vector;
using Mode = estep::HalfSpaceObstacles::Mode;

namespace
{
  /** V = 0: a flight that is 0 everywhere, with exact enclosures. */
  class ZeroFlight : public estep::FreeFlight
  {
  public:
    double
    value(const double) const override
    {
      return 0.;
    }

    estep::LineValue
    value_and_derivative(const double) const override
    {
      return {0., 0.};
    }

    estep::LineEnclosure
    enclose(const double, const double) const override
    {
      estep::LineEnclosure e = {{0., 0.}, {0., 0.}};
      e.curvature            = {0., 0.};
      return e;
    }
  };

  /**
   * Free points in 3D or 2D (V = 0, masses 1 + i / n), optionally with a fake
   * constraint of its own: an event at @p event_s (if <= s_max) with the
   * normal e_x on point 0.
   */
  class FreeParticles : public estep::MechanicalSystem
  {
  public:
    explicit FreeParticles(const unsigned int    n,
                           std::optional<double> event_s = std::nullopt,
                           const unsigned int    dim     = 3)
      : inv_mass(dim * n)
      , event_s(event_s)
      , dim(dim)
    {
      for (unsigned int i = 0; i < dim * n; ++i)
        inv_mass[i] = 1. / (1. + (i / dim) / double(n));
    }

    std::string
    name() const override
    {
      return "free particles";
    }

    unsigned int
    spatial_dimension() const override
    {
      return dim;
    }

    unsigned int
    n_dofs() const override
    {
      return inv_mass.size();
    }

    const Vector &
    inverse_mass() const override
    {
      return inv_mass;
    }

    double
    energy(const Vector &) const override
    {
      return 0.;
    }

    void
    gradient(const Vector &q, Vector &g) const override
    {
      g.reinit(q.size());
    }

    std::unique_ptr<estep::FreeFlight>
    free_flight(const Vector &, const Vector &) const override
    {
      return std::make_unique<ZeroFlight>();
    }

    std::optional<estep::ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &,
                           const double s_max) const override
    {
      if (!event_s || *event_s > s_max)
        return std::nullopt;
      estep::ConstraintEvent e;
      e.s = *event_s;
      e.normal.reinit(q.size());
      e.normal[0] = 1.;
      return e;
    }

  private:
    Vector                inv_mass;
    std::optional<double> event_s;
    unsigned int          dim;
  };

  HalfSpace
  half_space(const std::array<double, 3> &p, const std::array<double, 3> &n)
  {
    HalfSpace h;
    h.point  = p;
    h.normal = n;
    return h;
  }

  /** The floor z = 0. */
  HalfSpace
  floor_plane()
  {
    return half_space({{0., 0., 0.}}, {{0., 0., 1.}});
  }

  /** A ramp through (0.8, 0, 0) rising in x at 30 degrees: the free side is
   * z >= tan(30) (x - 0.8). */
  HalfSpace
  ramp()
  {
    return half_space({{0.8, 0., 0.}}, {{-0.5, 0., std::sqrt(0.75)}});
  }

  /** The reflection of @p v on @p normal, as energy-stepping makes it. */
  void
  reflect(const estep::MechanicalSystem &system,
          const Vector                  &normal,
          Vector                        &v)
  {
    const Vector &inverse_mass = system.inverse_mass();
    double        a = 0., m = 0.;
    for (unsigned int i = 0; i < v.size(); ++i)
      {
        a += normal[i] * v[i];
        m += normal[i] * normal[i] * inverse_mass[i];
      }
    const double lambda = -2. * a / m;
    for (unsigned int i = 0; i < v.size(); ++i)
      v[i] += lambda * inverse_mass[i] * normal[i];
  }

  /** The point of an event normal (the one with non-zero entries). */
  unsigned int
  event_point(const Vector &normal)
  {
    for (unsigned int i = 0; i < normal.size(); ++i)
      if (normal[i] != 0.)
        return i / 3;
    return std::numeric_limits<unsigned int>::max();
  }

  /** An elastic cube of n^3 hexahedra (24 tetrahedra each) filling [lower,
   * upper], lambda0 = 10, mu0 = 5, rho = 1. */
  template <typename Body = estep::ElasticBody>
  std::shared_ptr<const Body>
  cube(const std::array<double, 3> &lower,
       const std::array<double, 3> &upper,
       const unsigned int           n = 2)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n, lower, upper);
    return std::make_shared<const Body>(
      tria, std::make_shared<estep::NeoHookean>(10., 5.), 1., "cube");
  }

  /** The cube as a one-body ContactSystem (no contact of its own): its
   * boundary points and its rigid motion. */
  std::shared_ptr<const estep::ContactSystem>
  cube_system(const std::array<double, 3> &lower,
              const std::array<double, 3> &upper)
  {
    estep::ContactParameters p;
    p.mode = estep::ContactParameters::Mode::none;
    return std::make_shared<const estep::ContactSystem>(
      std::vector<std::shared_ptr<const estep::ElasticBody>>{
        cube(lower, upper)},
      p,
      "cube");
  }

  Vector
  random_vector(const unsigned int n, const double amplitude, const int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    Vector                                 v(n);
    for (auto &x : v)
      x = u(rng);
    return v;
  }
} // namespace



// ---------------------------------------------------------------------------
// Obstacle contacts (impenetrability).

TEST(HalfSpaceObstacles, RuleAtTheStartOfAFlight)
{
  auto                     base = std::make_shared<const FreeParticles>(4);
  const HalfSpaceObstacles obstacles(base,
                                     {floor_plane()},
                                     {0, 1, 2, 3},
                                     Mode::impenetrability);
  Vector                   q(12), v(12);
  // Point 0 behind the floor moving out, point 1 behind it and at rest,
  // point 2 on it moving along it, point 3 in front moving out.
  q[2]  = -0.1;
  v[2]  = 1.;
  q[5]  = -0.2;
  q[6]  = 0.3;
  v[6]  = 1.;
  q[11] = 0.5;
  v[11] = 2.;
  EXPECT_FALSE(obstacles.first_constraint_event(q, v, 1.));
  EXPECT_EQ(obstacles.n_points_behind(q), 2u);
  EXPECT_EQ(obstacles.max_penetration(q), 0.2);

  // Point 2 on the floor, moving in: a contact now, on its z coordinate.
  v[8] = -1.;
  const std::optional<estep::ConstraintEvent> on =
    obstacles.first_constraint_event(q, v, 1.);
  ASSERT_TRUE(on);
  EXPECT_EQ(on->s, 0.);
  for (unsigned int i = 0; i < 12; ++i)
    EXPECT_EQ(on->normal[i], i == 8 ? 1. : 0.);
  // After the reflection it moves out: no contact any more.
  reflect(obstacles, on->normal, v);
  EXPECT_GT(v[8], 0.);
  EXPECT_FALSE(obstacles.first_constraint_event(q, v, 1.));

  // Point 0, behind, moving in: a contact now too.
  v[2]              = -1.;
  const auto behind = obstacles.first_constraint_event(q, v, 1.);
  ASSERT_TRUE(behind);
  EXPECT_EQ(behind->s, 0.);
  EXPECT_EQ(event_point(behind->normal), 0u);

  // Point 3 in front, moving in: the crossing, a little before (not after)
  // it, and only if it comes before s_max.
  v[2]             = 0.;
  v[11]            = -2.;
  const auto ahead = obstacles.first_constraint_event(q, v, 1.);
  ASSERT_TRUE(ahead);
  EXPECT_EQ(event_point(ahead->normal), 3u);
  EXPECT_LE(ahead->s, 0.25);
  EXPECT_GT(ahead->s, 0.25 * (1. - 1e-14));
  EXPECT_FALSE(obstacles.first_constraint_event(q, v, 0.2));
}

// Random points in front of random planes, moving towards them: the reported
// contact is the first, a little before the exact crossing, and leaves every
// point in front of every plane as the integrator computes the positions;
// after the reflection the point is no contact at s = 0.
TEST(HalfSpaceObstacles, ContactsAreConservativeInFloatingPoint)
{
  const unsigned int                     n_points = 8;
  std::mt19937                           rng(5);
  std::uniform_real_distribution<double> u(-1., 1.);
  unsigned int                           n_cases = 0, n_touching = 0;
  double min_distance = std::numeric_limits<double>::infinity();
  double min_bands = min_distance, max_bands = 0.;
  for (unsigned int trial = 0; trial < 400; ++trial)
    {
      // A plane through a random point with a random normal (the floor
      // every fourth trial), points in front of it moving towards it.
      std::vector<HalfSpace> planes;
      if (trial % 4 == 0)
        planes.push_back(floor_plane());
      else
        planes.push_back(
          half_space({{u(rng), u(rng), u(rng)}}, {{u(rng), u(rng), u(rng)}}));
      auto base = std::make_shared<const FreeParticles>(n_points);
      const HalfSpaceObstacles obstacles(base,
                                         planes,
                                         {0, 1, 2, 3, 4, 5, 6, 7},
                                         Mode::impenetrability);
      const HalfSpace         &plane = obstacles.half_spaces()[0];
      Vector                   q(3 * n_points), v(3 * n_points);
      for (unsigned int i = 0; i < n_points; ++i)
        {
          const double distance =
            0.5 * (1. + u(rng)) * std::pow(10., -3. * (1. + u(rng)));
          for (unsigned int c = 0; c < 3; ++c)
            {
              q[3 * i + c] =
                plane.point[c] + distance * plane.normal[c] + 3. * u(rng);
              v[3 * i + c] = u(rng) - 2. * plane.normal[c];
            }
          // Back in front at the chosen distance after the tangential shift.
          const double d = obstacles.signed_distance(q, i, 0);
          for (unsigned int c = 0; c < 3; ++c)
            q[3 * i + c] += (distance - d) * plane.normal[c];
        }
      if (obstacles.n_points_behind(q) > 0)
        continue;
      const auto event = obstacles.first_constraint_event(q, v, 1e3);
      ASSERT_TRUE(event);
      ++n_cases;
      const unsigned int p = event_point(event->normal);
      // The earliest exact crossing, and this point's.
      double first = std::numeric_limits<double>::infinity(), own = 0.;
      for (unsigned int i = 0; i < n_points; ++i)
        {
          double rate = 0.;
          for (unsigned int c = 0; c < 3; ++c)
            rate += plane.normal[c] * v[3 * i + c];
          if (rate < 0.)
            {
              const double s = obstacles.signed_distance(q, i, 0) / -rate;
              first          = std::min(first, s);
              if (i == p)
                own = s;
            }
        }
      EXPECT_LE(event->s, own);
      EXPECT_LE(event->s, first);
      EXPECT_GE(event->s, first - 1e-11) << "trial " << trial;
      if (event->s == 0.)
        ++n_touching;
      // The end of the flight as energy-stepping computes it.
      Vector q_end = q;
      q_end.add(event->s, v);
      EXPECT_EQ(obstacles.n_points_behind(q_end), 0u) << "trial " << trial;
      const double d_end = obstacles.signed_distance(q_end, p, 0);
      min_distance       = std::min(min_distance, d_end);
      const double bands = d_end / obstacles.touching_band(q_end, p, 0);
      min_bands          = std::min(min_bands, bands);
      max_bands          = std::max(max_bands, bands);
      // Reflected, the point is no contact at the start of the next flight.
      reflect(obstacles, event->normal, v);
      const auto next = obstacles.first_constraint_event(q_end, v, 1e3);
      if (next)
        {
          EXPECT_TRUE(next->s > 0. || event_point(next->normal) != p)
            << "trial " << trial;
        }
    }
  std::cout << n_cases << " random contacts (" << n_touching
            << " at s = 0): smallest distance of the hitting point after "
               "the flight "
            << min_distance << ", " << min_bands << " to " << max_bands
            << " touching bands" << std::endl;
  EXPECT_GT(n_cases, 350u);
  EXPECT_GE(min_distance, 0.);
}

// In 2D: a point at (1, 1) moving with (-1, -1) towards the line x + y = 0
// reaches it at s = 1.
TEST(HalfSpaceObstacles, ContactsIn2D)
{
  auto base = std::make_shared<const FreeParticles>(2, std::nullopt, 2);
  EXPECT_THROW(HalfSpaceObstacles(base,
                                  {half_space({{0., 0., 0.}}, {{1., 1., 1.}})},
                                  {0},
                                  Mode::impenetrability),
               std::invalid_argument);
  const HalfSpaceObstacles obstacles(base,
                                     {half_space({{0., 0., 0.}},
                                                 {{1., 1., 0.}})},
                                     {0, 1},
                                     Mode::impenetrability);
  Vector                   q(4), v(4);
  q[0] = q[1] = 1.;
  v[0] = v[1]  = -1.;
  q[2]         = 3.;
  const auto e = obstacles.first_constraint_event(q, v, 2.);
  ASSERT_TRUE(e);
  EXPECT_LE(e->s, 1.);
  EXPECT_GT(e->s, 1. - 1e-14);
  EXPECT_NEAR(e->normal[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(e->normal[1], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(e->normal[2], 0.);
  EXPECT_EQ(e->normal[3], 0.);
  q.add(e->s, v);
  EXPECT_EQ(obstacles.n_points_behind(q), 0u);
  EXPECT_GE(obstacles.signed_distance(q, 0, 0), 0.);
  q.add(1e-3, v);
  EXPECT_EQ(obstacles.n_points_behind(q), 1u);
}

TEST(HalfSpaceObstacles, EarliestOfBaseAndObstacleEvents)
{
  Vector q(6), v(6);
  q[2] = 1.;
  v[2] = -1.;
  q[5] = 1.;
  for (const double base_s : {0.5, 2.})
    {
      auto base = std::make_shared<const FreeParticles>(2, base_s);
      const HalfSpaceObstacles obstacles(base,
                                         {floor_plane()},
                                         {0},
                                         Mode::impenetrability);
      const auto               e = obstacles.first_constraint_event(q, v, 10.);
      ASSERT_TRUE(e);
      if (base_s < 1.)
        {
          EXPECT_EQ(e->s, base_s);
          EXPECT_EQ(e->normal[0], 1.);
        }
      else
        {
          EXPECT_LE(e->s, 1.);
          EXPECT_GT(e->s, 1. - 1e-14);
          EXPECT_EQ(e->normal[2], 1.);
        }
      // The penalty mode has no events of its own.
      const HalfSpaceObstacles penalty(
        base, {floor_plane()}, {0}, Mode::penalty, 1e-3);
      const auto p = penalty.first_constraint_event(q, v, 10.);
      ASSERT_TRUE(p);
      EXPECT_EQ(p->s, base_s);
    }
}

TEST(HalfSpaceObstacles, RejectsBadInput)
{
  auto base = std::make_shared<const FreeParticles>(2);
  EXPECT_THROW(HalfSpaceObstacles(base,
                                  {half_space({{0., 0., 0.}}, {{0., 0., 0.}})},
                                  {0},
                                  Mode::impenetrability),
               std::invalid_argument);
  EXPECT_THROW(
    HalfSpaceObstacles(base, {floor_plane()}, {2}, Mode::impenetrability),
    std::invalid_argument);
  EXPECT_THROW(HalfSpaceObstacles(base, {floor_plane()}, {0}, Mode::penalty),
               std::invalid_argument);
  // Normals are normalised.
  const HalfSpaceObstacles o(base,
                             {half_space({{0., 0., 1.}}, {{0., 3., 4.}})},
                             {1, 0, 1},
                             Mode::impenetrability);
  EXPECT_NEAR(o.half_spaces()[0].normal[1], 0.6, 1e-16);
  EXPECT_EQ(o.points(), (std::vector<unsigned int>{0, 1}));
  EXPECT_EQ(o.observable_names().back(), "points_behind_obstacles");
}



// ---------------------------------------------------------------------------
// Penalty mode: derivatives and flight enclosures.

TEST(HalfSpaceObstacles, PenaltyGradientAndHessian)
{
  using Body      = estep::ElasticBodyWithHessian;
  const auto body = cube<Body>({{-0.5, -0.5, -0.1}}, {{0.5, 0.5, 0.9}});
  // The boundary points: a coordinate on the box.
  std::vector<unsigned int> points;
  const Vector              X = body->reference_configuration();
  for (unsigned int i = 0; i < body->n_vertices(); ++i)
    for (unsigned int c = 0; c < 3; ++c)
      if (std::abs(std::abs(X[3 * i + c] - (c == 2 ? 0.4 : 0.)) - 0.5) < 1e-12)
        {
          points.push_back(i);
          break;
        }
  EXPECT_EQ(points.size(), 50u);
  const double             eps = 1e-2;
  const HalfSpaceObstacles obstacles(
    body, {floor_plane(), ramp()}, points, Mode::penalty, eps);
  Vector q = X;
  q += random_vector(q.size(), 0.02, 3);
  q.add(
    1.2,
    body->rigid_velocity(X, {{0.7, 0., 0.}}, {{0., 0., 0.}}, {{0., 0., 0.}}));
  const unsigned int behind      = obstacles.n_points_behind(q);
  unsigned int       behind_ramp = 0;
  for (const unsigned int i : points)
    if (obstacles.signed_distance(q, i, 1) < 0.)
      ++behind_ramp;
  EXPECT_GT(behind_ramp, 5u);
  std::cout << behind << " of " << points.size()
            << " boundary points behind a plane (" << behind_ramp
            << " behind the ramp), obstacle energy "
            << obstacles.obstacle_energy(q) << " of " << obstacles.energy(q)
            << std::endl;
  ASSERT_GT(behind, 10u);
  ASSERT_GT(obstacles.obstacle_energy(q), 0.1 * obstacles.energy(q));

  Vector g;
  obstacles.gradient(q, g);
  double worst = 0.;
  for (unsigned int i = 0; i < q.size(); ++i)
    {
      const double step = 1e-6;
      Vector       qp = q, qm = q;
      qp[i] += step;
      qm[i] -= step;
      const double fd =
        (obstacles.energy(qp) - obstacles.energy(qm)) / (2. * step);
      worst = std::max(worst, std::abs(fd - g[i]) / (1. + std::abs(g[i])));
    }
  std::cout << "gradient against central differences: largest relative "
               "difference "
            << worst << std::endl;
  EXPECT_LT(worst, 1e-6);

  // The Hessian against central differences of the gradient, along random
  // directions.
  ASSERT_TRUE(obstacles.has_hessian());
  dealii::SparseMatrix<double> H(obstacles.hessian_sparsity());
  obstacles.hessian(q, H);
  for (unsigned int k = 0; k < 3; ++k)
    {
      const Vector dir = random_vector(q.size(), 1., 10 + k);
      Vector       Hd(q.size()), gp, gm;
      H.vmult(Hd, dir);
      const double step = 1e-6;
      Vector       qp = q, qm = q;
      qp.add(step, dir);
      qm.add(-step, dir);
      obstacles.gradient(qp, gp);
      obstacles.gradient(qm, gm);
      gp -= gm;
      gp /= 2. * step;
      gp -= Hd;
      EXPECT_LT(gp.l2_norm(), 1e-5 * Hd.l2_norm());
    }
}

namespace
{
  struct EnclosureFigures
  {
    unsigned long samples = 0, outside = 0, slopes_outside_curvature = 0,
                  across_crossings = 0, bad_samples = 0;
  };

  /**
   * Check the enclosure of @p flight over [a, b]: 11 sampled values and
   * slopes lie in it, the difference quotients of the slopes in its
   * curvature (up to their round-off), and its sample is what
   * value_and_derivative() computes.
   */
  void
  check_enclosure(const estep::FreeFlight &flight,
                  const double             a,
                  const double             b,
                  EnclosureFigures        &r)
  {
    const estep::LineEnclosure    e = flight.enclose(a, b);
    std::vector<estep::LineValue> samples;
    std::vector<double>           s;
    for (unsigned int j = 0; j <= 10; ++j)
      {
        s.push_back(j == 10 ? b : a + (b - a) * j / 10.);
        samples.push_back(flight.value_and_derivative(s.back()));
        ++r.samples;
        if (!e.value.contains(samples.back().value) ||
            !e.derivative.contains(samples.back().derivative))
          ++r.outside;
      }
    if (std::isfinite(e.curvature.lower) && std::isfinite(e.curvature.upper))
      for (unsigned int j = 0; j < 10; ++j)
        {
          const double ds = s[j + 1] - s[j];
          const double q =
            (samples[j + 1].derivative - samples[j].derivative) / ds;
          const double noise = 1e-12 *
                                 (std::abs(samples[j].derivative) +
                                  std::abs(samples[j + 1].derivative) + 1.) /
                                 ds +
                               1e-9 * std::max(std::abs(e.curvature.lower),
                                               std::abs(e.curvature.upper));
          if (q < e.curvature.lower - noise || q > e.curvature.upper + noise)
            ++r.slopes_outside_curvature;
        }
    if (e.sample_point >= a && e.sample_point <= b)
      {
        const estep::LineValue at = flight.value_and_derivative(e.sample_point);
        if (at.value != e.sample.value || at.derivative != e.sample.derivative)
          ++r.bad_samples;
      }
  }

  /**
   * Enclosures of the flight of @p obstacles from (q, v) over intervals about
   * each crossing of a plane by a point (widths from 1e-8 to 1 times the
   * crossing time, the crossing at a random place inside) and over random
   * intervals of [0, span].
   */
  void
  check_flight(const HalfSpaceObstacles &obstacles,
               const Vector             &q,
               const Vector             &v,
               const double              span,
               std::mt19937             &rng,
               EnclosureFigures         &r)
  {
    std::uniform_real_distribution<double> u(0., 1.);
    const auto                             flight = obstacles.free_flight(q, v);
    const double limit = 0.999 * flight->admissible_limit();
    for (unsigned int k = 0; k < obstacles.half_spaces().size(); ++k)
      for (const unsigned int i : obstacles.points())
        {
          const HalfSpace &plane = obstacles.half_spaces()[k];
          double           rate  = 0.;
          for (unsigned int c = 0; c < 3; ++c)
            rate += plane.normal[c] * v[3 * i + c];
          const double crossing = -obstacles.signed_distance(q, i, k) / rate;
          if (!(crossing > 0.) || !(crossing < std::min(span, limit)))
            continue;
          const double width = crossing * std::pow(10., -8. * u(rng));
          const double a     = std::max(0., crossing - width * u(rng));
          const double b     = std::min(a + width, limit);
          if (!(a < b))
            continue;
          ++r.across_crossings;
          check_enclosure(*flight, a, b, r);
        }
    for (unsigned int j = 0; j < 8; ++j)
      {
        const double width =
          std::min(span, limit) * std::pow(10., -6. * u(rng));
        const double a = (std::min(span, limit) - width) * u(rng);
        check_enclosure(*flight, a, a + width, r);
      }
  }
} // namespace

// Free points against two planes: the flight is the penalty term alone, so
// its curvature is exactly the sum of the pairs' (the kinks included).
TEST(HalfSpaceObstacles, PenaltyEnclosuresOfFreePoints)
{
  const unsigned int        n    = 20;
  auto                      base = std::make_shared<const FreeParticles>(n);
  std::vector<unsigned int> points(n);
  for (unsigned int i = 0; i < n; ++i)
    points[i] = i;
  const HalfSpaceObstacles obstacles(
    base, {floor_plane(), ramp()}, points, Mode::penalty, 1e-3);
  std::mt19937     rng(7);
  EnclosureFigures r;
  for (unsigned int trial = 0; trial < 40; ++trial)
    {
      const Vector q = random_vector(3 * n, 1., 100 + trial);
      const Vector v = random_vector(3 * n, 1., 200 + trial);
      check_flight(obstacles, q, v, 3., rng, r);
      // At s = 0 the flight is the energy, within its value tolerance.
      const auto flight = obstacles.free_flight(q, v);
      EXPECT_LE(std::abs(flight->value(0.) - obstacles.energy(q)),
                flight->value_tolerance());
      EXPECT_EQ(flight->value(0.), obstacles.energy(q));
      EXPECT_GT(flight->value_tolerance(), 0.);
    }
  std::cout << r.samples << " sampled values and slopes (" << r.across_crossings
            << " intervals across a crossing): " << r.outside
            << " outside their enclosures, " << r.slopes_outside_curvature
            << " slope differences outside the curvature, " << r.bad_samples
            << " wrong samples" << std::endl;
  EXPECT_GT(r.across_crossings, 200u);
  EXPECT_EQ(r.outside, 0u);
  EXPECT_EQ(r.slopes_outside_curvature, 0u);
  EXPECT_EQ(r.bad_samples, 0u);
}



// ---------------------------------------------------------------------------
// The elastic cube bouncing under energy-stepping.

namespace
{
  struct BounceFigures
  {
    unsigned long steps = 0, constraint_events = 0, climbs = 0, descents = 0;
    double        energy_error = 0., terrace_excursion = -1.;
    unsigned int  max_behind = 0, max_behind_in_one_step = 0;
    double        max_penetration = 0.;
    /** Centre-of-mass velocity at the start and the end; lowest z of the
     * centre of mass. */
    std::array<double, 3> v_start = {{0., 0., 0.}}, v_end = {{0., 0., 0.}};
    double                lowest_centre = 1e300;
    /** The largest changes of the x and y momentum. */
    double           change_x = 0., change_y = 0.;
    double           momentum_scale = 0.;
    bool             reached_end    = false;
    EnclosureFigures enclosures;
  };

  /**
   * The cube [-0.5, 0.5]^2 x [0.05, 1.05] (2^3 hexahedra, 71 points, 50 on
   * the boundary) with a small random deformation, moving with @p velocity
   * against the obstacles @p planes in @p mode until @p t_end; energy step
   * 1e-3 of the kinetic energy. After every step: points behind a plane,
   * terraced-energy error, momenta; with @p sample_enclosures, the
   * enclosures of every fourth flight.
   */
  BounceFigures
  bounce(const std::vector<HalfSpace> &planes,
         const Mode                    mode,
         const double                  eps,
         const std::array<double, 3>  &velocity,
         const double                  t_end,
         const bool                    sample_enclosures = false)
  {
    const auto base = cube_system({{-0.5, -0.5, 0.05}}, {{0.5, 0.5, 1.05}});
    const auto obstacles = std::make_shared<const HalfSpaceObstacles>(
      base, planes, estep::boundary_points(*base), mode, eps);
    EXPECT_EQ(obstacles->points().size(), 50u);
    // A small random deformation puts V(q0) inside a terrace (the undeformed
    // cube has V = 0 to round-off, on a level).
    Vector q0 = base->body(0).reference_configuration();
    q0 += random_vector(q0.size(), 1e-3, 11);
    const Vector v0 = base->body(0).rigid_velocity(q0,
                                                   velocity,
                                                   {{0., 0., 0.}},
                                                   {{0., 0., 0.}});
    const double T0 = estep::kinetic_energy(*obstacles, v0);

    estep::EnergyStepping integrator(*obstacles, 1e-3 * T0);
    integrator.initialize(0., q0, v0);
    const double         E0 = integrator.terraced_energy();
    const estep::Momenta m0 = estep::compute_momenta(*obstacles, q0, v0);
    BounceFigures        r;
    r.momentum_scale =
      std::sqrt(m0.linear[0] * m0.linear[0] + m0.linear[1] * m0.linear[1] +
                m0.linear[2] * m0.linear[2]);
    r.v_start = base->system_motion(q0, v0).velocity;
    std::mt19937 rng(17);
    double       last_step = 0.;
    while (integrator.time() < t_end)
      {
        if (sample_enclosures && r.steps % 4 == 0)
          check_flight(*obstacles,
                       integrator.position(),
                       integrator.velocity(),
                       std::max(2. * last_step, 1e-6),
                       rng,
                       r.enclosures);
        const double t_before = integrator.time();
        integrator.step(t_end);
        last_step = integrator.time() - t_before;
        ++r.steps;
        const Vector      &q      = integrator.position();
        const Vector      &v      = integrator.velocity();
        const unsigned int behind = obstacles->n_points_behind(q);
        r.max_behind              = std::max(r.max_behind, behind);
        r.max_penetration =
          std::max(r.max_penetration, obstacles->max_penetration(q));
        r.energy_error =
          std::max(r.energy_error,
                   std::abs(integrator.terraced_energy() - E0) / E0);
        r.terrace_excursion =
          std::max(r.terrace_excursion,
                   estep_test::terrace_excursion(integrator, 16));
        const estep::Momenta m = estep::compute_momenta(*obstacles, q, v);
        r.change_x = std::max(r.change_x, std::abs(m.linear[0] - m0.linear[0]));
        r.change_y = std::max(r.change_y, std::abs(m.linear[1] - m0.linear[1]));
        r.lowest_centre =
          std::min(r.lowest_centre, base->system_motion(q, v).centre[2]);
        if (r.steps >= 50000 || r.energy_error > 1e-6)
          break;
      }
    r.reached_end = integrator.time() >= t_end;
    r.v_end = base->system_motion(integrator.position(), integrator.velocity())
                .velocity;
    for (const auto &c : integrator.counters())
      {
        if (c.first == "constraint events")
          r.constraint_events = c.second;
        if (c.first == "climbs")
          r.climbs = c.second;
        if (c.first == "descents")
          r.descents = c.second;
      }
    std::cout << (mode == Mode::penalty ? "penalty" : "impenetrability")
              << (mode == Mode::penalty ? " eps " + std::to_string(eps) : "")
              << ", " << planes.size() << " plane(s): " << r.steps
              << " steps to t = " << integrator.time() << ", "
              << r.constraint_events << " constraint events, " << r.climbs
              << " climbs, " << r.descents
              << " descents; terraced energy error " << r.energy_error
              << "; excursion beyond a level " << r.terrace_excursion
              << " h; points behind at most " << r.max_behind << " (depth "
              << r.max_penetration << "); centre velocity (" << r.v_start[0]
              << ", " << r.v_start[1] << ", " << r.v_start[2] << ") -> ("
              << r.v_end[0] << ", " << r.v_end[1] << ", " << r.v_end[2]
              << "), lowest centre z " << r.lowest_centre
              << "; largest change of P_x " << r.change_x / r.momentum_scale
              << ", of P_y " << r.change_y / r.momentum_scale << " (relative)"
              << std::endl;
    if (sample_enclosures)
      std::cout << "  " << r.enclosures.samples
                << " sampled values and slopes ("
                << r.enclosures.across_crossings
                << " intervals across a crossing): " << r.enclosures.outside
                << " outside, " << r.enclosures.slopes_outside_curvature
                << " slope differences outside the curvature, "
                << r.enclosures.bad_samples << " wrong samples" << std::endl;
    return r;
  }
} // namespace

TEST(HalfSpaceObstacles, CubeBouncesOnTheFloor)
{
  const BounceFigures r =
    bounce({floor_plane()}, Mode::impenetrability, 0., {{0.3, 0., -1.}}, 0.6);
  EXPECT_TRUE(r.reached_end);
  EXPECT_EQ(r.max_behind, 0u);
  EXPECT_GT(r.constraint_events, 10u);
  EXPECT_LT(r.energy_error, 1e-12);
  EXPECT_LT(r.terrace_excursion, 1e-8);
  // The normal momentum reversed; the tangential one unchanged (the floor
  // has no friction and its normal no tangential component).
  EXPECT_LT(r.v_start[2], -0.99);
  EXPECT_GT(r.v_end[2], 0.5);
  EXPECT_LT(r.change_x, 1e-12 * r.momentum_scale);
  EXPECT_LT(r.change_y, 1e-12 * r.momentum_scale);
  EXPECT_NEAR(r.v_end[0], 0.3, 1e-12);
}

// The cube slides into the corner of the floor and a ramp: both stop it, and
// the momentum along y, which neither normal has a component of, stays.
TEST(HalfSpaceObstacles, CubeBouncesOnFloorAndRamp)
{
  const BounceFigures r = bounce(
    {floor_plane(), ramp()}, Mode::impenetrability, 0., {{1., 0.2, -0.5}}, 2.);
  EXPECT_TRUE(r.reached_end);
  EXPECT_EQ(r.max_behind, 0u);
  EXPECT_GT(r.constraint_events, 10u);
  EXPECT_LT(r.energy_error, 1e-12);
  EXPECT_LT(r.terrace_excursion, 1e-8);
  EXPECT_LT(r.v_end[0], 0.9);
  EXPECT_GT(r.v_end[2], 0.);
  EXPECT_LT(r.change_y, 1e-12 * r.momentum_scale);
  EXPECT_GT(r.change_x, 0.1 * r.momentum_scale);
}

TEST(HalfSpaceObstacles, PenaltyCubeBounces)
{
  for (const bool with_ramp : {false, true})
    {
      std::vector<HalfSpace> planes = {floor_plane()};
      if (with_ramp)
        planes.push_back(ramp());
      const BounceFigures r =
        bounce(planes,
               Mode::penalty,
               1e-3,
               with_ramp ? std::array<double, 3>{{1., 0.2, -0.5}} :
                           std::array<double, 3>{{0.3, 0., -1.}},
               with_ramp ? 2. : 0.6,
               true);
      EXPECT_TRUE(r.reached_end);
      EXPECT_LT(r.energy_error, 1e-12);
      EXPECT_LT(r.terrace_excursion, 1e-8);
      EXPECT_EQ(r.constraint_events, 0u);
      EXPECT_GT(r.max_behind, 0u);
      EXPECT_LT(r.max_penetration, 0.05);
      EXPECT_GT(r.v_end[2], 0.);
      EXPECT_LT(r.change_y, 1e-12 * r.momentum_scale);
      if (!with_ramp)
        {
          EXPECT_GT(r.v_end[2], 0.5);
          EXPECT_LT(r.change_x, 1e-12 * r.momentum_scale);
        }
      EXPECT_GT(r.enclosures.across_crossings, 30u);
      EXPECT_EQ(r.enclosures.outside, 0u);
      EXPECT_EQ(r.enclosures.slopes_outside_curvature, 0u);
      EXPECT_EQ(r.enclosures.bad_samples, 0u);
    }
}

// A soft penalty does not stop the cube: it passes the plane whole (every
// boundary point behind it at once), conserving the terraced energy.
TEST(HalfSpaceObstacles, SoftPenaltyLetsTheCubePass)
{
  const BounceFigures r =
    bounce({floor_plane()}, Mode::penalty, 100., {{0., 0., -1.}}, 1.5);
  EXPECT_TRUE(r.reached_end);
  EXPECT_LT(r.energy_error, 1e-12);
  EXPECT_EQ(r.max_behind, 50u);
  EXPECT_LT(r.lowest_centre, -0.5);
}
