// The contact system: ball mesh, layout, gradient against central differences,
// free-flight enclosures against samples (second-order forms of single
// triangle pairs in generic and degenerate motions, and of whole flights),
// observables, parameters.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <estep/composite/contact_system.h>
#include <estep/contact/penalty_contact.h>
#include <estep/contact/penalty_flight.h>
#include <estep/contact/triangle_intersection.h>
#include <estep/fem/ball_mesh.h>

#include <gtest/gtest.h>

#include "contact_test_bodies.h"

#include <array>
#include <cmath>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

using estep::ContactParameters;
using estep::Vector;

namespace
{
  ContactParameters
  penalty_parameters(const double eps)
  {
    ContactParameters p;
    p.mode              = ContactParameters::Mode::penalty;
    p.penalty_parameter = eps;
    return p;
  }

  // Two overlapping coarse balls (built once).
  const estep::ContactSystem &
  overlapping_balls()
  {
    static const auto system =
      estep_test::two_balls(1.8, 0.6, penalty_parameters(1e-2));
    return *system;
  }
} // namespace

TEST(BallMesh, SeedSizeAndReproducible)
{
  dealii::Triangulation<3> tria, again;
  estep::make_ball_mesh(tria);
  estep::make_ball_mesh(again);
  double volume = 0.;
  for (const auto &cell : tria.active_cell_iterators())
    volume += cell->measure();
  std::cout << "ball mesh (size 0.3): " << tria.n_active_cells()
            << " tetrahedra, " << tria.n_vertices() << " vertices, volume "
            << volume << std::endl;
  EXPECT_GT(tria.n_active_cells(), 600u);
  EXPECT_LT(tria.n_active_cells(), 1200u);
  EXPECT_GT(tria.n_vertices(), 150u);
  EXPECT_LT(tria.n_vertices(), 350u);
  EXPECT_NEAR(volume, 4. / 3. * M_PI, 0.15 * 4.);
  ASSERT_EQ(tria.n_vertices(), again.n_vertices());
  ASSERT_EQ(tria.n_active_cells(), again.n_active_cells());
  for (unsigned int i = 0; i < tria.n_vertices(); ++i)
    {
      EXPECT_EQ(tria.get_vertices()[i], again.get_vertices()[i]);
    }
  // Boundary vertices on the unit sphere.
  for (const auto &face : tria.active_face_iterators())
    if (face->at_boundary())
      for (const unsigned int v : face->vertex_indices())
        {
          EXPECT_NEAR(face->vertex(v).norm(), 1., 1e-14);
        }
}

TEST(ContactSystem, LayoutAndBoundaryMap)
{
  const auto &system = overlapping_balls();
  ASSERT_EQ(system.n_bodies(), 2u);
  EXPECT_EQ(system.n_dofs(), system.body(0).n_dofs() + system.body(1).n_dofs());
  EXPECT_EQ(system.point_offset(1), system.body(0).n_vertices());
  const Vector q = estep_test::reference(system);
  // Every boundary triangle's points lie on its body's sphere, and the
  // triangles are oriented outward.
  const double centre[2] = {0., 1.8};
  for (unsigned int t = 0; t < system.boundary_triangles().size(); ++t)
    {
      const auto        &tri = system.boundary_triangles()[t];
      const unsigned int b   = system.triangle_bodies()[t];
      double             x[3][3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          ASSERT_GE(tri[k], system.point_offset(b));
          ASSERT_LT(tri[k],
                    system.point_offset(b) + system.body(b).n_vertices());
          for (unsigned int d = 0; d < 3; ++d)
            x[k][d] = q[3 * tri[k] + d] - (d == 0 ? centre[b] : 0.);
          EXPECT_NEAR(std::sqrt(x[k][0] * x[k][0] + x[k][1] * x[k][1] +
                                x[k][2] * x[k][2]),
                      1.,
                      1e-12);
        }
      double n[3];
      for (unsigned int d = 0; d < 3; ++d)
        {
          const unsigned int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
          n[d] = (x[1][d1] - x[0][d1]) * (x[2][d2] - x[0][d2]) -
                 (x[1][d2] - x[0][d2]) * (x[2][d1] - x[0][d1]);
        }
      EXPECT_GT(n[0] * x[0][0] + n[1] * x[0][1] + n[2] * x[0][2], 0.);
    }
}

TEST(ContactSystem, IntersectingPairsOfAKeptTreeAsByBruteForce)
{
  // The system keeps the tree of intersecting_pairs() and refits it from
  // call to call (anew every 64 calls): over 80 configurations in which ball
  // 2 sweeps through ball 1 and out again, deformed and turned, the pairs are
  // those of the exact test on every pair of triangles of the two balls, in
  // increasing order.
  const auto        &system     = overlapping_balls();
  const auto        &tris       = system.boundary_triangles();
  const auto        &body       = system.triangle_bodies();
  const Vector       X          = estep_test::reference(system);
  const Vector       noise      = estep_test::random_vector(X.size(), 1e-2, 5);
  const unsigned int first      = system.point_offset(1);
  unsigned int       with_pairs = 0;
  for (unsigned int k = 0; k < 80; ++k)
    {
      // Ball 2 (centre 1.8 on the x axis) moves to x = 0.9 + 2.4 |sin|,
      // turning about the z axis through its centre.
      const double shift = 2.4 * std::abs(std::sin(0.05 * k)) - 0.9;
      const double angle = 0.1 * k;
      Vector       q     = X;
      q += noise;
      for (unsigned int i = first; i < X.size() / 3; ++i)
        {
          const double x = X[3 * i] - 1.8, y = X[3 * i + 1];
          q[3 * i] = 1.8 + shift + std::cos(angle) * x - std::sin(angle) * y;
          q[3 * i + 1] = std::sin(angle) * x + std::cos(angle) * y;
        }
      std::vector<std::pair<unsigned int, unsigned int>> expected;
      for (unsigned int i = 0; i < tris.size(); ++i)
        for (unsigned int j = i + 1; j < tris.size(); ++j)
          if (body[i] != body[j] &&
              estep::contact::triangles_intersect(
                estep::contact::triangle_at(q.data(), tris[i]),
                estep::contact::triangle_at(q.data(), tris[j])))
            expected.emplace_back(i, j);
      EXPECT_EQ(system.intersecting_pairs(q), expected)
        << "configuration " << k;
      with_pairs += !expected.empty();
    }
  EXPECT_GT(with_pairs, 20u);
  EXPECT_LT(with_pairs, 70u);
}

TEST(ContactSystem, GradientMatchesCentralDifferences)
{
  const auto &system = overlapping_balls();
  Vector      q      = estep_test::reference(system);
  q += estep_test::random_vector(q.size(), 1e-3, 3);
  ASSERT_GT(system.contact_energy(q), 0.);
  ASSERT_GT(system.n_intersecting_pairs(q), 10u);
  std::cout << "overlapping balls: " << system.n_intersecting_pairs(q)
            << " intersecting pairs, contact energy "
            << system.contact_energy(q) << ", total " << system.energy(q)
            << std::endl;

  Vector g;
  system.gradient(q, g);
  // Zero net force and torque of the whole gradient.
  double force[3] = {0., 0., 0.}, torque[3] = {0., 0., 0.}, scale = 0.;
  for (unsigned int i = 0; i < q.size() / 3; ++i)
    for (unsigned int d = 0; d < 3; ++d)
      {
        const unsigned int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
        force[d] += g[3 * i + d];
        torque[d] +=
          q[3 * i + d1] * g[3 * i + d2] - q[3 * i + d2] * g[3 * i + d1];
        scale += std::abs(g[3 * i + d]);
      }
  for (unsigned int d = 0; d < 3; ++d)
    {
      EXPECT_LT(std::abs(force[d]), 1e-12 * scale);
      EXPECT_LT(std::abs(torque[d]), 1e-12 * scale * 3.);
    }

  // Directional derivatives along random directions.
  double worst = 0.;
  for (unsigned int k = 0; k < 10; ++k)
    {
      const Vector d  = estep_test::random_vector(q.size(), 1., 100 + k);
      const double h  = 1e-6;
      Vector       qp = q, qm = q;
      qp.add(h, d);
      qm.add(-h, d);
      const double fd    = (system.energy(qp) - system.energy(qm)) / (2. * h);
      const double exact = g * d;
      worst = std::max(worst, std::abs(fd - exact) / std::abs(exact));
    }
  std::cout << "gradient vs central differences: worst relative error " << worst
            << std::endl;
  EXPECT_LT(worst, 1e-6);

  // The contact part alone, on the dofs that carry it.
  Vector                         gc(q.size());
  estep::contact::PenaltyContact contact(system.boundary_triangles(), 1e-2);
  contact.set_exclusion_groups(system.triangle_bodies());
  contact.add_gradient(q.data(), q.size(), gc.data());
  EXPECT_NEAR(contact.energy(q.data(), q.size()),
              system.contact_energy(q),
              1e-14 * system.contact_energy(q));
  double worst_component = 0., largest = gc.linfty_norm();
  for (unsigned int i = 0; i < q.size(); ++i)
    if (std::abs(gc[i]) > 0.01 * largest)
      {
        const double h  = 1e-7;
        Vector       qp = q, qm = q;
        qp[i] += h;
        qm[i] -= h;
        const double fd = (contact.energy(qp.data(), qp.size()) -
                           contact.energy(qm.data(), qm.size())) /
                          (2. * h);
        worst_component =
          std::max(worst_component, std::abs(fd - gc[i]) / largest);
      }
  std::cout << "contact gradient components: worst error / max "
            << worst_component << std::endl;
  EXPECT_LT(worst_component, 1e-5);
}

TEST(ContactSystem, FlightValuesMatchEnergy)
{
  const auto  &system = overlapping_balls();
  Vector       q      = estep_test::reference(system);
  const Vector v      = estep_test::random_vector(q.size(), 0.2, 7);
  const auto   flight = system.free_flight(q, v);
  for (const double s : {0., 0.01, 0.1, 0.3})
    {
      Vector x = q;
      x.add(s, v);
      const double V = system.energy(x);
      EXPECT_NEAR(flight->value(s), V, 1e-12 * std::abs(V));
      const auto lv = flight->value_and_derivative(s);
      EXPECT_NEAR(lv.value, V, 1e-12 * std::abs(V));
      Vector g;
      system.gradient(x, g);
      EXPECT_NEAR(lv.derivative, g * v, 1e-10 * std::abs(g * v) + 1e-12);
    }
}

TEST(ContactSystem, EnclosuresContainSampledValues)
{
  const auto                            &system = overlapping_balls();
  const Vector                           q      = estep_test::reference(system);
  std::mt19937_64                        rng(5);
  std::uniform_real_distribution<double> u(0., 1.);
  unsigned int                           n_samples = 0, n_failures = 0;
  unsigned int                           n_curved = 0, n_curvature_samples = 0;
  for (unsigned int flight_number = 0; flight_number < 4; ++flight_number)
    {
      // Random deformation velocities plus an approach of the two balls.
      Vector v = estep_test::random_vector(q.size(), 0.3, 50 + flight_number);
      for (unsigned int i = system.point_offset(1); i < q.size() / 3; ++i)
        v[3 * i] -= 1.;
      const auto   flight = system.free_flight(q, v);
      const double limit  = std::min(0.3, 0.999 * flight->admissible_limit());
      for (unsigned int k = 0; k < 25; ++k)
        {
          const double width = limit * std::pow(10., -4. * u(rng));
          const double a     = (limit - width) * u(rng);
          const double b     = a + width;
          const auto   e     = flight->enclose(a, b);
          // The centre sample is what value_and_derivative() computes there.
          ASSERT_TRUE(e.sample_point >= a && e.sample_point <= b);
          const auto at_sample = flight->value_and_derivative(e.sample_point);
          EXPECT_EQ(e.sample.value, at_sample.value);
          EXPECT_EQ(e.sample.derivative, at_sample.derivative);
          const bool curved = std::isfinite(e.curvature.lower) &&
                              std::isfinite(e.curvature.upper);
          n_curved += curved;
          for (unsigned int j = 0; j <= 20; ++j)
            {
              const double s  = a + (b - a) * j / 20.;
              const auto   lv = flight->value_and_derivative(s);
              // V'' by central differences of V' inside the curvature bound.
              const double delta = 1e-3 * (b - a);
              if (curved && s - delta >= a && s + delta <= b)
                {
                  const double curvature =
                    (flight->value_and_derivative(s + delta).derivative -
                     flight->value_and_derivative(s - delta).derivative) /
                    (2. * delta);
                  const double slack =
                    1e-6 * (std::abs(e.curvature.lower) +
                            std::abs(e.curvature.upper)) +
                    1e-12 * (std::abs(lv.derivative) + 1.) / delta;
                  ++n_curvature_samples;
                  EXPECT_GE(curvature, e.curvature.lower - slack)
                    << "[" << a << ", " << b << "] s = " << s;
                  EXPECT_LE(curvature, e.curvature.upper + slack)
                    << "[" << a << ", " << b << "] s = " << s;
                }
              ++n_samples;
              if (!e.value.contains(lv.value) ||
                  !e.derivative.contains(lv.derivative))
                {
                  ++n_failures;
                  ADD_FAILURE()
                    << "s = " << s << " in [" << a << ", " << b << "]: value "
                    << lv.value << " not in [" << e.value.lower << ", "
                    << e.value.upper << "] or slope " << lv.derivative
                    << " not in [" << e.derivative.lower << ", "
                    << e.derivative.upper << "]";
                }
            }
        }
    }
  std::cout << n_samples << " samples, " << n_failures
            << " outside their enclosures; " << n_curved
            << " enclosures of 100 bound V'' (" << n_curvature_samples
            << " difference quotients checked)" << std::endl;
  EXPECT_EQ(n_failures, 0u);
  EXPECT_GT(n_curved, 0u);
}

TEST(ContactSystem, PenaltyEnclosuresTighten)
{
  const auto  &system = overlapping_balls();
  const Vector q      = estep_test::reference(system);
  Vector       v      = estep_test::random_vector(q.size(), 0.1, 77);
  estep::contact::PenaltyContact contact(system.boundary_triangles(), 1e-2);
  contact.set_exclusion_groups(system.triangle_bodies());
  estep::contact::PenaltyFlight flight(contact, q.data(), v.data(), q.size());
  const double                  s = 0.05;
  const double                  I = flight.value(s);
  ASSERT_GT(I, 0.);
  std::cout << "penalty enclosure about s = " << s << " (I = " << I
            << ", dI/ds = " << flight.value_and_derivative(s).second << "):";
  double previous = 0.;
  for (const double w : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6})
    {
      const auto e = flight.enclose(s - w / 2, s + w / 2);
      std::cout << " width " << w << ": value " << e.value.width() << ", slope "
                << e.derivative.width() << ";";
      EXPECT_TRUE(e.value.contains(I));
      if (w <= 1e-4)
        {
          EXPECT_LT(e.value.width(), 1e-2 * I);
          EXPECT_LT(e.value.width(), 0.2 * previous);
        }
      previous = e.value.width();
    }
  std::cout << std::endl;
}

// Random pairs of triangles moving on straight lines (generic, nearly
// parallel, a vertex sliding in the other plane, far from the origin) on
// intervals of widths 1e-8 ... 1 about times near their contact: the
// enclosures of the second-order form hold the computed g and g' (as the
// penalty energy evaluates them) at 21 points each.
TEST(ContactSystem, PenaltyPairFormsHoldSampledValues)
{
  std::mt19937_64                        rng(2024);
  std::uniform_real_distribution<double> u(-1., 1.), u01(0., 1.);
  unsigned int n_samples = 0, n_outside = 0, n_positive = 0, n_smooth = 0,
               n_bounded = 0, n_forms = 4000;
  for (unsigned int trial = 0; trial < n_forms; ++trial)
    {
      const unsigned int kind = trial % 4;
      double             x0[9], w0[9], x1[9], w1[9];
      for (unsigned int i = 0; i < 9; ++i)
        {
          x0[i] = u(rng);
          w0[i] = u(rng);
        }
      // T1 about a point of T0 at s0.
      const double s0 = u01(rng), b0 = u01(rng), b1 = u01(rng) * (1. - b0);
      double       c[3];
      for (unsigned int k = 0; k < 3; ++k)
        c[k] = (1. - b0 - b1) * (x0[k] + s0 * w0[k]) +
               b0 * (x0[3 + k] + s0 * w0[3 + k]) +
               b1 * (x0[6 + k] + s0 * w0[6 + k]);
      const double size = std::pow(10., -3. * u01(rng));
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const unsigned int n = 3 * i + k;
            // Nearly parallel: a shrunk copy of T0, slightly tilted.
            const double offset =
              kind == 1 ? 0.7 * (x0[n] + s0 * w0[n] - c[k]) + 1e-3 * u(rng) :
                          u(rng);
            w1[n] = kind == 1 ? w0[n] + 1e-2 * u(rng) : u(rng);
            x1[n] = c[k] + size * offset - s0 * w1[n];
          }
      if (kind == 2)
        // Vertex 0 of T1 moves with a point of T0's plane.
        for (unsigned int k = 0; k < 3; ++k)
          {
            x1[k] = 0.5 * x0[k] + 0.3 * x0[3 + k] + 0.2 * x0[6 + k];
            w1[k] = 0.5 * w0[k] + 0.3 * w0[3 + k] + 0.2 * w0[6 + k];
          }
      if (kind == 3)
        {
          const double shift = std::pow(10., 3. * u01(rng));
          for (unsigned int i = 0; i < 9; ++i)
            {
              x0[i] += shift;
              x1[i] += shift;
            }
        }
      const double m = s0 + 0.1 * u(rng) * std::pow(10., -6. * u01(rng));
      const double r = std::pow(10., -8. * u01(rng));
      const estep::LineTaylorForm interval =
        estep::LineTaylorForm::about_centre_of(m - r, m + r);
      const estep::LineTaylorForm form =
        estep::contact::squared_intersection_length_form(
          x0, w0, x1, w1, interval.centre, interval.radius);
      const estep::LineEnclosure e = form.enclosure();
      n_smooth += form.curvature.width() > 0.;
      n_bounded += std::isfinite(e.derivative.width());
      for (unsigned int j = 0; j <= 20; ++j)
        {
          const double              s = m - r + 2. * r * j / 20.;
          estep::contact::Triangle3 T[2];
          std::array<double, 18>    gradient;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              {
                T[0][i][k] = x0[3 * i + k] + s * w0[3 * i + k];
                T[1][i][k] = x1[3 * i + k] + s * w1[3 * i + k];
              }
          const double g =
            estep::contact::squared_intersection_length(T[0], T[1], &gradient);
          double slope = 0.;
          for (unsigned int n = 0; n < 9; ++n)
            slope += gradient[n] * w0[n] + gradient[9 + n] * w1[n];
          ++n_samples;
          n_positive += g > 0.;
          if (!e.value.contains(g) || !e.derivative.contains(slope))
            {
              ++n_outside;
              ADD_FAILURE()
                << "kind " << kind << ", r = " << r
                << ", s - m = " << s - form.centre << ": g = " << g << " in ["
                << e.value.lower << ", " << e.value.upper << "]? g' = " << slope
                << " in [" << e.derivative.lower << ", " << e.derivative.upper
                << "]?";
            }
        }
    }
  std::cout << n_forms << " pair forms (" << n_smooth << " with a curvature, "
            << n_bounded << " bounded), " << n_samples << " samples ("
            << n_positive << " with g > 0), " << n_outside
            << " outside their enclosures" << std::endl;
  EXPECT_EQ(n_outside, 0u);
  EXPECT_GT(n_positive, n_samples / 2);
  EXPECT_GT(n_smooth, n_forms / 5);
}

TEST(ContactSystem, ObservablesOfRigidMotions)
{
  const auto  &system = overlapping_balls();
  const Vector q      = estep_test::reference(system);
  const Vector v =
    estep_test::rigid_velocities(system,
                                 q,
                                 {{{1., 2., 3.}}, {{0., 0., 0.}}},
                                 {{{0., 0., 0.}}, {{0., 0., 2.5}}});
  const auto names  = system.observable_names();
  const auto values = system.observables(q, v);
  ASSERT_EQ(names.size(), 19u);
  ASSERT_EQ(values.size(), names.size());
  EXPECT_EQ(names[0], "V1_x");
  EXPECT_EQ(names[9], "Omega2_x");
  EXPECT_EQ(names[12], "V_x");
  EXPECT_EQ(names[18], "intersecting_pairs");
  EXPECT_NEAR(values[0], 1., 1e-13);
  EXPECT_NEAR(values[1], 2., 1e-13);
  EXPECT_NEAR(values[2], 3., 1e-13);
  for (unsigned int i = 3; i < 6; ++i)
    EXPECT_NEAR(values[i], 0., 1e-13);
  // Spin 2.5 about z: Omega = Theta omega / m, 2/5 R^2 omega = 1 for a
  // homogeneous ball; the lumped masses of the coarse mesh sit further out and
  // the coarse mesh is not isotropic.
  EXPECT_LT(std::abs(values[9]), 0.1);
  EXPECT_LT(std::abs(values[10]), 0.1);
  EXPECT_GT(values[11], 0.8);
  EXPECT_LT(values[11], 1.4);
  // The system's Omega about its centre of mass: the spin part plus the orbital
  // part of the two centres, both recomputed here.
  const auto m1 = system.body_motion(q, v, 0), m2 = system.body_motion(q, v, 1);
  const auto all = system.system_motion(q, v);
  EXPECT_NEAR(all.mass, m1.mass + m2.mass, 1e-14 * all.mass);
  double expected_z = m1.mass * m1.angular[2] + m2.mass * m2.angular[2];
  for (const auto *m : {&m1, &m2})
    expected_z +=
      m->mass *
      ((m->centre[0] - all.centre[0]) * (m->velocity[1] - all.velocity[1]) -
       (m->centre[1] - all.centre[1]) * (m->velocity[0] - all.velocity[0]));
  EXPECT_NEAR(values[17], expected_z / all.mass, 1e-12);
  EXPECT_EQ(values[18], double(system.n_intersecting_pairs(q)));
  EXPECT_GT(values[18], 0.);
}

TEST(ContactParameters, DeclareParseAndErrors)
{
  dealii::ParameterHandler prm;
  ContactParameters::declare_parameters(prm);
  prm.parse_input_from_string("subsection Contact\n"
                              "  set Mode = impenetrability\n"
                              "  set Collision tolerance = 1e-5\n"
                              "  set Self contact = true\n"
                              "end\n");
  ContactParameters p;
  p.parse_parameters(prm);
  EXPECT_EQ(p.mode, ContactParameters::Mode::impenetrability);
  EXPECT_EQ(p.ccd_tolerance, 1e-5);
  EXPECT_TRUE(p.self_contact);
  EXPECT_FALSE(p.is_default());
  EXPECT_EQ(ContactParameters::mode_name(p.mode), "impenetrability");
  EXPECT_ANY_THROW(ContactParameters::parse_mode("glue"));
  dealii::ParameterHandler bad;
  ContactParameters::declare_parameters(bad);
  EXPECT_ANY_THROW(bad.parse_input_from_string(
    "subsection Contact\n  set Mode = glue\nend\n"));
  // A setting the mode does not use is an error, not ignored.
  for (const char *text :
       {"set Mode = impenetrability\nset Penalty parameter = 1e-3\n",
        "set Mode = penalty\nset Collision tolerance = 1e-5\n",
        "set Mode = none\nset Self contact = true\n"})
    {
      dealii::ParameterHandler unused;
      ContactParameters::declare_parameters(unused);
      unused.parse_input_from_string(std::string("subsection Contact\n") +
                                     text + "end\n");
      EXPECT_THROW(ContactParameters().parse_parameters(unused),
                   std::runtime_error)
        << text;
    }
  ContactParameters        defaults;
  dealii::ParameterHandler plain;
  ContactParameters::declare_parameters(plain);
  defaults.parse_parameters(plain);
  EXPECT_TRUE(defaults.is_default());
}
