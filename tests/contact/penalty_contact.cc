// Penalty contact: gradient of g against central differences, the energy of a
// mesh against a brute-force sum, free-flight evaluation (and the candidates
// of the search's flight on every interval), rigid-motion invariance, bad
// input.

#include <estep/contact/penalty_contact.h>
#include <estep/contact/penalty_flight.h>

#include <gtest/gtest.h>

#include "test_meshes.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace estep::contact;

namespace
{
  Triangle3
  random_triangle(std::mt19937_64 &rng)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    Triangle3                              T;
    for (auto &p : T)
      for (double &x : p)
        x = u(rng);
    return T;
  }

  /** Two spheres of radius 1, 0.5 apart, the second moving towards the
   * first at unit speed. */
  struct ApproachingSpheres
  {
    std::vector<double>          q, v;
    std::vector<TriangleIndices> tris;

    ApproachingSpheres()
    {
      estep_test::add_sphere(q, tris, 0., 0., 0., 1., 8, 12);
      const std::size_t n_first = q.size();
      estep_test::add_sphere(q, tris, 2.5, 0., 0., 1., 9, 11);
      v.assign(q.size(), 0.);
      for (std::size_t i = n_first; i < q.size(); i += 3)
        v[i] = -1.;
    }
  };
} // namespace

TEST(PenaltyContact, GradientOfGapMatchesCentralDifferences)
{
  std::mt19937_64 rng(21);
  unsigned int    n_checked = 0;
  double          worst     = 0.;
  while (n_checked < 2000)
    {
      Triangle3 T[2] = {random_triangle(rng), random_triangle(rng)};
      std::array<double, 18> grad;
      const double g0 = squared_intersection_length(T[0], T[1], &grad);
      if (g0 < 1e-4)
        continue;
      const double h   = 1e-6;
      double       err = 0., norm = 0.;
      bool         smooth = true;
      for (unsigned int d = 0; d < 18 && smooth; ++d)
        {
          Triangle3 Tp[2] = {T[0], T[1]}, Tm[2] = {T[0], T[1]};
          Tp[d / 9][(d % 9) / 3][d % 3] += h;
          Tm[d / 9][(d % 9) / 3][d % 3] -= h;
          const TriangleIntersection r0 = intersect_triangles(T[0], T[1]);
          const TriangleIntersection rp = intersect_triangles(Tp[0], Tp[1]);
          const TriangleIntersection rm = intersect_triangles(Tm[0], Tm[1]);
          // Skip the rare pairs where a perturbation switches an end point's
          // generator (g is only piecewise smooth there).
          for (unsigned int i = 0; i < 2; ++i)
            smooth = smooth && rp.kind == r0.kind && rm.kind == r0.kind &&
                     rp.source[i].edge == r0.source[i].edge &&
                     rm.source[i].edge == r0.source[i].edge &&
                     rp.source[i].edge_triangle == r0.source[i].edge_triangle &&
                     rm.source[i].edge_triangle == r0.source[i].edge_triangle;
          const double fd = (squared_intersection_length(Tp[0], Tp[1]) -
                             squared_intersection_length(Tm[0], Tm[1])) /
                            (2. * h);
          err  = std::max(err, std::abs(fd - grad[d]));
          norm = std::max(norm, std::abs(grad[d]));
        }
      if (!smooth)
        continue;
      worst = std::max(worst, err / norm);
      ASSERT_LT(err, 1e-6 * std::max(1., norm)) << "pair " << n_checked;
      // No net force and no net torque (rigid-motion invariance of g).
      for (unsigned int k = 0; k < 3; ++k)
        {
          double f = 0.;
          for (unsigned int v = 0; v < 6; ++v)
            f += grad[3 * v + k];
          EXPECT_NEAR(f, 0., 1e-10 * norm);
        }
      double torque[3] = {0., 0., 0.};
      for (unsigned int v = 0; v < 6; ++v)
        {
          const Point3 &x = T[v / 3][v % 3];
          const double *f = &grad[3 * v];
          torque[0] += x[1] * f[2] - x[2] * f[1];
          torque[1] += x[2] * f[0] - x[0] * f[2];
          torque[2] += x[0] * f[1] - x[1] * f[0];
        }
      for (const double t : torque)
        EXPECT_NEAR(t, 0., 1e-10 * norm);
      ++n_checked;
    }
  std::cout << "gradient checks: " << n_checked << ", worst relative error "
            << worst << std::endl;
}

namespace
{
  /** Two overlapping spheres. */
  void
  two_spheres(std::vector<double> &q, std::vector<TriangleIndices> &tris)
  {
    estep_test::add_sphere(q, tris, 0., 0., 0., 1., 8, 12);
    estep_test::add_sphere(q, tris, 1.7, 0.2, 0.1, 1., 9, 11);
  }

  double
  brute_force_energy(const std::vector<double>          &q,
                     const std::vector<TriangleIndices> &tris,
                     const double                        eps,
                     unsigned int                       &count)
  {
    double sum = 0.;
    count      = 0;
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (std::size_t j = i + 1; j < tris.size(); ++j)
        {
          if (share_vertex(tris[i], tris[j]))
            continue;
          Triangle3 A, B;
          for (unsigned int v = 0; v < 3; ++v)
            for (unsigned int k = 0; k < 3; ++k)
              {
                A[v][k] = q[3 * tris[i][v] + k];
                B[v][k] = q[3 * tris[j][v] + k];
              }
          const double g = squared_intersection_length(A, B);
          count += (g > 0.);
          sum += g;
        }
    return sum / (2. * eps);
  }
} // namespace

TEST(PenaltyContact, MeshEnergyMatchesBruteForceAndGradient)
{
  std::vector<double>          q;
  std::vector<TriangleIndices> tris;
  two_spheres(q, tris);
  const double   eps = 1e-3;
  PenaltyContact contact(tris, eps);
  unsigned int   count    = 0;
  const double   expected = brute_force_energy(q, tris, eps, count);
  EXPECT_GT(count, 10u);
  EXPECT_DOUBLE_EQ(contact.energy(q.data(), q.size()), expected);
  EXPECT_EQ(contact.n_intersecting_pairs(q.data(), q.size()), count);

  std::vector<double> g(q.size(), 0.);
  EXPECT_DOUBLE_EQ(contact.add_gradient(q.data(), q.size(), g.data()),
                   expected);
  // Directional derivative against a central difference along a random
  // direction.
  std::mt19937_64                        rng(22);
  std::uniform_real_distribution<double> u(-1., 1.);
  std::vector<double>                    d(q.size()), qp(q), qm(q);
  double                                 slope = 0.;
  for (std::size_t i = 0; i < q.size(); ++i)
    {
      d[i] = u(rng);
      slope += g[i] * d[i];
      qp[i] += 1e-7 * d[i];
      qm[i] -= 1e-7 * d[i];
    }
  const double fd = (contact.energy(qp.data(), qp.size()) -
                     contact.energy(qm.data(), qm.size())) /
                    2e-7;
  EXPECT_NEAR(fd, slope, 1e-5 * std::abs(slope));
  // Net force zero.
  for (unsigned int k = 0; k < 3; ++k)
    {
      double f = 0., scale = 0.;
      for (std::size_t i = k; i < g.size(); i += 3)
        f += g[i], scale += std::abs(g[i]);
      EXPECT_NEAR(f, 0., 1e-12 * scale);
    }
}

TEST(PenaltyContact, FreeFlightMatchesDirectEvaluation)
{
  const ApproachingSpheres            spheres;
  const std::vector<double>          &q = spheres.q, &v = spheres.v;
  const std::vector<TriangleIndices> &tris = spheres.tris;
  PenaltyContact                      contact(tris, 1e-2);
  const auto flight = contact.flight(q.data(), v.data(), q.size(), 1.);
  EXPECT_GT(flight.n_candidate_pairs(), 0u);
  unsigned int n_positive = 0;
  for (unsigned int i = 0; i <= 20; ++i)
    {
      const double        s = i / 20.;
      std::vector<double> x(q.size());
      for (std::size_t k = 0; k < q.size(); ++k)
        x[k] = q[k] + s * v[k];
      const double direct = contact.energy(x.data(), x.size());
      EXPECT_DOUBLE_EQ(flight.value(s), direct) << "s = " << s;
      EXPECT_EQ(flight.n_intersecting_pairs(s),
                contact.n_intersecting_pairs(x.data(), x.size()));
      std::vector<double> g(q.size(), 0.);
      contact.add_gradient(x.data(), x.size(), g.data());
      double slope = 0.;
      for (std::size_t k = 0; k < q.size(); ++k)
        slope += g[k] * v[k];
      EXPECT_NEAR(flight.value_and_derivative(s).second,
                  slope,
                  1e-12 * (1. + std::abs(slope)));
      n_positive += (direct > 0.);
    }
  EXPECT_GT(n_positive, 5u);
  EXPECT_EQ(flight.value(0.), 0.);
}

// The flight the search uses keeps as candidates of a query over [a, b] only
// the pairs whose boxes swept over [a, b] overlap. Two spheres 0.5 apart
// approach at unit speed, and the queries come as in a search (the start,
// then intervals, their halves, smaller ones further on): every query's
// enclosure must hold the energy evaluated directly, by a broad phase of its
// own, and every value must be that energy.
TEST(PenaltyContact, FlightCandidatesKeepEveryPairMeetingOnTheInterval)
{
  const ApproachingSpheres            spheres;
  const std::vector<double>          &q = spheres.q, &v = spheres.v;
  const std::vector<TriangleIndices> &tris = spheres.tris;
  const PenaltyContact                contact(tris, 1e-2);
  const PenaltyFlight flight(contact, q.data(), v.data(), q.size());
  const auto          direct = [&](const double s) {
    std::vector<double> x(q.size());
    for (std::size_t k = 0; k < q.size(); ++k)
      x[k] = q[k] + s * v[k];
    return contact.energy(x.data(), x.size());
  };
  EXPECT_EQ(flight.value(0.), 0.);
  unsigned int n_positive = 0;
  for (const auto &[a, b] : std::vector<std::pair<double, double>>{
         {0., 1.}, {0., 0.5}, {0.5, 1.}, {0.5, 0.75}, {0.6, 0.62}, {0.9, 1.}})
    {
      const estep::LineEnclosure e = flight.enclose(a, b);
      for (unsigned int i = 0; i <= 10; ++i)
        {
          const double s = a + (b - a) * i / 10.;
          const double I = direct(s);
          EXPECT_TRUE(e.value.contains(I))
            << "I(" << s << ") = " << I << " outside [" << e.value.lower << ", "
            << e.value.upper << "], the enclosure over [" << a << ", " << b
            << "]";
          n_positive += I > 0.;
        }
    }
  for (unsigned int i = 0; i <= 20; ++i)
    EXPECT_DOUBLE_EQ(flight.value(i / 20.), direct(i / 20.)) << i / 20.;
  EXPECT_GT(n_positive, 20u);
}

// A flight's value at a point must not depend on the queries made before it:
// an enclosure's sample is taken for what an evaluation at its point gives,
// and the search compares values from both. The broad phase a query starts
// covers a window that depends on the query, and the tree over that window
// finds the pairs in its own order; the values are the same to the last bit
// only if the pairs are summed in an order of their own.
TEST(PenaltyContact, FlightValuesDoNotDependOnEarlierQueries)
{
  const ApproachingSpheres   spheres;
  const std::vector<double> &q = spheres.q, &v = spheres.v;
  const PenaltyContact       contact(spheres.tris, 1e-2);
  using Query = std::function<void(const PenaltyFlight &)>;
  const std::vector<std::pair<std::string, Query>> before = {
    {"nothing", [](const PenaltyFlight &) {}},
    {"enclose(0.6, 0.7)", [](const PenaltyFlight &f) { f.enclose(0.6, 0.7); }},
    {"value(0.2)", [](const PenaltyFlight &f) { f.value(0.2); }},
    {"enclose(0, 1)", [](const PenaltyFlight &f) { f.enclose(0., 1.); }},
    {"enclose(0.64, 0.66)",
     [](const PenaltyFlight &f) { f.enclose(0.64, 0.66); }}};
  unsigned int n_positive = 0;
  for (const double s : {0.55, 0.62, 0.65, 0.7, 0.8})
    {
      const PenaltyFlight first(contact, q.data(), v.data(), q.size());
      const auto          reference = first.value_and_derivative(s);
      n_positive += reference.first > 0.;
      for (const auto &[name, query] : before)
        {
          const PenaltyFlight flight(contact, q.data(), v.data(), q.size());
          query(flight);
          const auto value = flight.value_and_derivative(s);
          EXPECT_EQ(std::memcmp(&value.first, &reference.first, sizeof(double)),
                    0)
            << "f(" << s << ") after " << name << ": " << value.first
            << " against " << reference.first;
          EXPECT_EQ(
            std::memcmp(&value.second, &reference.second, sizeof(double)), 0)
            << "f'(" << s << ") after " << name;
        }
    }
  EXPECT_GE(n_positive, 3u);
}

TEST(PenaltyContact, RigidMotionInvariance)
{
  std::vector<double>          q;
  std::vector<TriangleIndices> tris;
  two_spheres(q, tris);
  PenaltyContact      contact(tris, 1.);
  const double        e0 = contact.energy(q.data(), q.size());
  const double        c = std::cos(0.7), s = std::sin(0.7);
  std::vector<double> x(q.size());
  for (std::size_t i = 0; i < q.size(); i += 3)
    {
      x[i]     = c * q[i] - s * q[i + 1] + 3.;
      x[i + 1] = s * q[i] + c * q[i + 1] - 1.;
      x[i + 2] = q[i + 2] + 0.5;
    }
  EXPECT_NEAR(contact.energy(x.data(), x.size()), e0, 1e-12 * e0);
}

TEST(PenaltyContact, BadInputThrows)
{
  EXPECT_THROW(PenaltyContact({{{0, 1, 2}}}, 0.), std::invalid_argument);
  EXPECT_THROW(PenaltyContact({{{0, 1, 1}}}, 1.), std::invalid_argument);
  PenaltyContact      contact({{{0, 1, 2}}, {{3, 4, 5}}}, 1.);
  std::vector<double> q(9, 0.);
  EXPECT_THROW(contact.energy(q.data(), q.size()), std::invalid_argument);
  std::vector<double> v(9, 0.);
  EXPECT_THROW(contact.flight(q.data(), v.data(), 9, -1.),
               std::invalid_argument);
}
