// The P1 elastic body on the spinning cube: counts, mass, the spinning-cube
// initial energy and angular momentum, energy and gradient, invariance under
// rigid motions, bad meshes.
#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <estep/base/parallel_blocks.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>
#include <estep/materials/neo_hookean.h>

#include <gtest/gtest.h>

#include "test_bodies.h"

#include <cmath>
#include <cstring>
#include <map>
#include <vector>

namespace
{
  using estep_test::seed_cube;

  TEST(ElasticBody, SeedCubeCounts)
  {
    const auto &body = seed_cube();
    EXPECT_EQ(body.n_cells(), 12288u);
    EXPECT_EQ(body.n_vertices(), 2969u);
    EXPECT_EQ(body.n_dofs(), 3u * 2969u);
    EXPECT_EQ(body.spatial_dimension(), 3u);
  }

  TEST(ElasticBody, VolumeAndMass)
  {
    const auto &body = seed_cube();
    EXPECT_NEAR(body.volume(), 1., 1e-12);
    EXPECT_NEAR(body.mass(), 0.100, 1e-13);
    // Lumped mass: rho vol / 4 per vertex and cell.
    std::vector<double> m(body.n_vertices(), 0.);
    const auto         &d = body.cell_data();
    for (unsigned int e = 0; e < d.n_cells; ++e)
      for (unsigned int a = 0; a < 4; ++a)
        m[d.point[a][e]] += 0.25 * 0.1 * d.volume[e];
    for (unsigned int i = 0; i < body.n_vertices(); ++i)
      {
        EXPECT_NEAR(body.point_mass(i), m[i], 1e-16);
        EXPECT_EQ(body.inverse_mass()[3 * i], 1. / body.point_mass(i));
      }
  }

  TEST(ElasticBody, BoundaryFacesCloseOutwardWithTheirIds)
  {
    dealii::Triangulation<3> tria;
    dealii::GridGenerator::subdivided_hyper_cube_with_simplices(tria,
                                                                2,
                                                                0.,
                                                                2.);
    // Id 2 d + s on the side x_d = 2 s.
    for (const auto &cell : tria.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          for (unsigned int d = 0; d < 3; ++d)
            for (unsigned int side = 0; side < 2; ++side)
              if (face->center()[d] == 2. * side)
                face->set_boundary_id(2 * d + side);
    const estep::P1CellData data = estep::make_p1_cell_data(tria, 1.);
    ASSERT_EQ(data.boundary_triangle.size(), 6u * 4u * 2u);
    ASSERT_EQ(data.boundary_id.size(), data.boundary_triangle.size());
    const auto X = [&](const unsigned int p, const unsigned int c) {
      return data.reference_position[3 * p + c];
    };
    // Divergence theorem: the sum of centroid . area-normal / 3 is the
    // volume 8.
    double                                               volume = 0.;
    std::map<std::pair<unsigned int, unsigned int>, int> edge_use;
    std::vector<int>                                     faces_per_id(6, 0);
    for (unsigned int f = 0; f < data.boundary_triangle.size(); ++f)
      {
        const auto &t = data.boundary_triangle[f];
        double      a[3], b[3], n[3];
        for (unsigned int c = 0; c < 3; ++c)
          {
            a[c] = X(t[1], c) - X(t[0], c);
            b[c] = X(t[2], c) - X(t[0], c);
          }
        for (unsigned int c = 0; c < 3; ++c)
          n[c] = (a[(c + 1) % 3] * b[(c + 2) % 3] -
                  a[(c + 2) % 3] * b[(c + 1) % 3]) /
                 2.;
        for (unsigned int c = 0; c < 3; ++c)
          volume += (X(t[0], c) + X(t[1], c) + X(t[2], c)) / 3. * n[c] / 3.;
        for (unsigned int k = 0; k < 3; ++k)
          ++edge_use[{t[k], t[(k + 1) % 3]}];
        // On the side of its id, its normal outward.
        const unsigned int id = data.boundary_id[f];
        ASSERT_LT(id, 6u);
        ++faces_per_id[id];
        const unsigned int d = id / 2;
        for (unsigned int k = 0; k < 3; ++k)
          EXPECT_EQ(X(t[k], d), 2. * (id % 2));
        EXPECT_GT(n[d] * (id % 2 == 1 ? 1. : -1.), 0.);
      }
    EXPECT_NEAR(volume, 8., 1e-12);
    for (unsigned int id = 0; id < 6; ++id)
      EXPECT_EQ(faces_per_id[id], 8);
    // Closed and consistently oriented: every directed edge once, its reverse
    // once.
    for (const auto &[e, n] : edge_use)
      {
        EXPECT_EQ(n, 1);
        EXPECT_EQ(edge_use.count({e.second, e.first}), 1u);
      }
    dealii::Triangulation<3> hex;
    dealii::GridGenerator::hyper_cube(hex);
    EXPECT_THROW(estep::make_p1_cell_data(hex, 1.), dealii::ExceptionBase);
  }

  TEST(ElasticBody, BuiltFromItsCellDataAsFromItsMesh)
  {
    dealii::Triangulation<3> tria;
    dealii::GridGenerator::subdivided_hyper_cube_with_simplices(tria, 3);
    const auto material = std::make_shared<estep::NeoHookean>(0.0100, 0.0066);
    const estep::ElasticBody from_mesh(tria, material, 2.);
    const estep::ElasticBody from_data(estep::make_p1_cell_data(tria, 2.),
                                       material);
    EXPECT_EQ(from_data.density(), 2.);
    EXPECT_EQ(from_data.mass(), from_mesh.mass());
    EXPECT_EQ(from_data.volume(), from_mesh.volume());
    const estep::Vector q = from_mesh.reference_configuration();
    estep::Vector       x(q);
    for (unsigned int i = 0; i < x.size(); ++i)
      x[i] *= 1. + 0.01 * std::sin(i);
    EXPECT_EQ(from_data.energy(x), from_mesh.energy(x));
    // Incomplete arrays are refused, and so are cells short of this rank's.
    estep::P1CellData missing = estep::make_p1_cell_data(tria, 2.);
    missing.lumped_mass.pop_back();
    EXPECT_THROW(estep::ElasticBody(missing, material), dealii::ExceptionBase);
    estep::P1CellData part = estep::make_p1_cell_data(tria, 2.);
    part.for_each_cell_array([](auto &v) { v.resize(v.size() - 4); });
    EXPECT_THROW(estep::ElasticBody(part, material), dealii::ExceptionBase);
    // So are arrays without the table of the chunks they hold.
    estep::P1CellData unmapped = estep::make_p1_cell_data(tria, 2.);
    unmapped.chunk_start.clear();
    EXPECT_THROW(estep::ElasticBody(unmapped, material), dealii::ExceptionBase);
  }

  TEST(ElasticBody, SpinningCubeKineticEnergyAndAngularMomentum)
  {
    const auto         &body = seed_cube();
    const estep::Vector q    = body.reference_configuration();
    const estep::Vector v =
      body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, {{0.5, 0.5, 0.5}});
    const double T = estep::kinetic_energy(body, v);
    const auto   p = estep::compute_momenta(body, q, v);
    EXPECT_NEAR(T, 8.43099e-3, 0.5e-8);
    EXPECT_NEAR(std::abs(p.angular[2]), 1.686198e-2, 0.5e-8);
    EXPECT_NEAR(p.angular[2], 2. * T, 1e-15); // L = I omega, T = I omega^2 / 2
    for (unsigned int c = 0; c < 3; ++c)
      EXPECT_NEAR(p.linear[c], 0., 1e-16);
    EXPECT_NEAR(p.angular[0], 0., 1e-15);
    EXPECT_NEAR(p.angular[1], 0., 1e-15);
    RecordProperty("T0", std::to_string(T));
  }

  TEST(ElasticBody, UndeformedEnergyIsZero)
  {
    const auto         &body = seed_cube();
    const estep::Vector q    = body.reference_configuration();
    EXPECT_NEAR(body.energy(q), 0., 1e-15);
    estep::Vector g;
    body.gradient(q, g);
    EXPECT_LT(g.linfty_norm(), 1e-15);
  }

  TEST(ElasticBody, GradientMatchesCentralDifferences)
  {
    const auto          body = estep_test::cube_body(2);
    const estep::Vector q    = estep_test::perturbed(*body, 0.03, 11);
    ASSERT_TRUE(std::isfinite(body->energy(q)));
    estep::Vector g;
    body->gradient(q, g);
    const double scale = g.linfty_norm();
    ASSERT_GT(scale, 1e-6);
    for (unsigned int k = 0; k < body->n_dofs(); ++k)
      {
        const double  h  = 1e-6;
        estep::Vector qp = q, qm = q;
        qp[k] += h;
        qm[k] -= h;
        const double fd = (body->energy(qp) - body->energy(qm)) / (2. * h);
        EXPECT_NEAR(g[k], fd, 1e-7 * scale) << "dof " << k;
      }
    // Total force and torque of an invariant energy vanish.
    double force[3] = {0., 0., 0.}, torque[3] = {0., 0., 0.};
    for (unsigned int i = 0; i < body->n_vertices(); ++i)
      {
        const double *x = q.data() + 3 * i, *f = g.data() + 3 * i;
        for (unsigned int c = 0; c < 3; ++c)
          force[c] += f[c];
        torque[0] += x[1] * f[2] - x[2] * f[1];
        torque[1] += x[2] * f[0] - x[0] * f[2];
        torque[2] += x[0] * f[1] - x[1] * f[0];
      }
    for (unsigned int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(force[c], 0., 1e-14 * scale * body->n_vertices());
        EXPECT_NEAR(torque[c], 0., 1e-14 * scale * body->n_vertices());
      }
  }

  TEST(ElasticBody, GradientOnSeedCubeSampledDofs)
  {
    const auto         &body = seed_cube();
    const estep::Vector q    = estep_test::perturbed(body, 0.005, 12);
    estep::Vector       g;
    body.gradient(q, g);
    const double scale = g.linfty_norm();
    for (unsigned int k = 0; k < body.n_dofs(); k += 997)
      {
        const double  h  = 1e-6;
        estep::Vector qp = q, qm = q;
        qp[k] += h;
        qm[k] -= h;
        EXPECT_NEAR(g[k],
                    (body.energy(qp) - body.energy(qm)) / (2. * h),
                    1e-6 * scale);
      }
  }

  TEST(ElasticBody, InvariantUnderRigidMotion)
  {
    const auto         &body = seed_cube();
    const estep::Vector q    = estep_test::perturbed(body, 0.005, 13);
    // Rotation R about the axis (1, 2, 3)/|.| by 0.7 rad, then a translation.
    const double n[3] = {1. / std::sqrt(14.),
                         2. / std::sqrt(14.),
                         3. / std::sqrt(14.)};
    const double c = std::cos(0.7), s = std::sin(0.7);
    double       R[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        R[i][j] = (i == j ? c : 0.) + (1. - c) * n[i] * n[j];
    R[0][1] -= s * n[2];
    R[0][2] += s * n[1];
    R[1][0] += s * n[2];
    R[1][2] -= s * n[0];
    R[2][0] -= s * n[1];
    R[2][1] += s * n[0];
    const double  t[3] = {0.3, -1.2, 2.5};
    estep::Vector Q(q.size());
    for (unsigned int i = 0; i < body.n_vertices(); ++i)
      for (unsigned int a = 0; a < 3; ++a)
        {
          Q[3 * i + a] = t[a];
          for (unsigned int b = 0; b < 3; ++b)
            Q[3 * i + a] += R[a][b] * q[3 * i + b];
        }
    const double V = body.energy(q);
    ASSERT_GT(V, 0.);
    EXPECT_NEAR(body.energy(Q), V, 1e-12 * V);
    estep::Vector g, G;
    body.gradient(q, g);
    body.gradient(Q, G);
    const double scale = g.linfty_norm();
    for (unsigned int i = 0; i < body.n_vertices(); ++i)
      for (unsigned int a = 0; a < 3; ++a)
        {
          double Rg = 0.;
          for (unsigned int b = 0; b < 3; ++b)
            Rg += R[a][b] * g[3 * i + b];
          EXPECT_NEAR(G[3 * i + a], Rg, 1e-11 * scale);
        }
  }

  TEST(ElasticBody, InvertedConfigurationHasInfiniteEnergy)
  {
    const auto   &body = seed_cube();
    estep::Vector q    = body.reference_configuration();
    // Mirror the whole body: every cell inverted.
    for (unsigned int i = 0; i < body.n_vertices(); ++i)
      q[3 * i] = -q[3 * i];
    EXPECT_TRUE(std::isinf(body.energy(q)));
    EXPECT_GT(body.energy(q), 0.);
  }

  TEST(ElasticBody, RejectsInvertedCell)
  {
    // One tetrahedron with negative orientation.
    const std::vector<dealii::Point<3>> vertices = {{0., 0., 0.},
                                                    {1., 0., 0.},
                                                    {0., 1., 0.},
                                                    {0., 0., 1.}};
    std::vector<dealii::CellData<3>>    cells(1, dealii::CellData<3>(4));
    cells[0].vertices = {0, 2, 1, 3};
    dealii::Triangulation<3> tria;
    tria.create_triangulation(vertices, cells, dealii::SubCellData());
    try
      {
        estep::ElasticBody body(tria,
                                std::make_shared<estep::NeoHookean>(1., 1.),
                                1.);
        FAIL() << "an inverted cell was accepted";
      }
    catch (const std::exception &e)
      {
        EXPECT_NE(std::string(e.what()).find("inverted tetrahedron"),
                  std::string::npos)
          << e.what();
      }
  }

  TEST(ElasticBody, RejectsHexahedra)
  {
    dealii::Triangulation<3> tria;
    dealii::GridGenerator::hyper_cube(tria);
    try
      {
        estep::ElasticBody body(tria,
                                std::make_shared<estep::NeoHookean>(1., 1.),
                                1.);
        FAIL() << "a hexahedral mesh was accepted";
      }
    catch (const std::exception &e)
      {
        EXPECT_NE(std::string(e.what()).find("not a tetrahedron"),
                  std::string::npos)
          << e.what();
      }
  }

  // The lumped masses, to the last bit, whatever the number of threads: on a
  // structured mesh many cells are translates of the one before, whose
  // Jacobians deal.II's FEValues reuses on one thread and recomputes on
  // more, which changes the last bits of its values (the bar of
  // scene_bar_impact.prm).
  TEST(ElasticBody, LumpedMassesDoNotDependOnTheThreads)
  {
    estep::MeshDescription bar;
    bar.type      = "deal.II 24";
    bar.generator = "subdivided_hyper_rectangle";
    bar.arguments = "20, 2, 2 : 0, 0, 0 : 1, 0.1, 0.1 : false";
    dealii::Triangulation<3> tria;
    estep::make_mesh(bar, tria);
    std::vector<double> masses[2];
    for (const unsigned int threads : {1u, 2u})
      {
        estep::set_thread_count(threads);
        masses[threads - 1] = estep::make_p1_cell_data(tria, 1.).lumped_mass;
      }
    estep::set_thread_count(1);
    ASSERT_EQ(masses[0].size(), masses[1].size());
    for (std::size_t p = 0; p < masses[0].size(); ++p)
      ASSERT_EQ(std::memcmp(&masses[0][p], &masses[1][p], sizeof(double)), 0)
        << "point " << p << ": " << masses[0][p] << " on 1 thread, "
        << masses[1][p] << " on 2";
  }

  // The gradient's parts on several threads take the blocks of cells, and
  // a part owns the points whose first cell lies in its blocks. A ball of
  // gmsh of 3,085 cells has a last block of 13 cells whose points all belong
  // to earlier cells: on 3 threads (or 4 processes) the part of that block
  // owns no point, and must compute nothing (it once cleared a reversed
  // range of its forces and crashed).
  TEST(ElasticBody, GradientWhenAPartOwnsNoPoint)
  {
    estep::MeshDescription ball;
    ball.type      = "ball";
    ball.mesh_size = 0.1952;
    dealii::Triangulation<3> tria;
    estep::make_mesh(ball, tria);
    const estep::ElasticBody body(tria,
                                  std::make_shared<estep::NeoHookean>(1., 1.),
                                  1.);
    const estep::P1CellData &data = body.cell_data();
    ASSERT_EQ(data.n_cells, 3085u);
    const unsigned int last_block = (data.n_cells - 1) / estep::block_size;
    for (unsigned int p = 0; p < data.n_points; ++p)
      ASSERT_LT(data.first_cell[p], last_block * estep::block_size)
        << "the last block owns point " << p << ": not the case tested";

    const estep::Vector q = estep_test::perturbed(body, 0.01, 5);
    estep::Vector       serial, parallel;
    estep::set_thread_count(1);
    body.gradient(q, serial);
    for (const unsigned int threads : {2u, 3u, 4u})
      {
        estep::set_thread_count(threads);
        body.gradient(q, parallel);
        EXPECT_EQ(std::memcmp(parallel.data(),
                              serial.data(),
                              serial.size() * sizeof(double)),
                  0)
          << threads << " threads";
      }
    estep::set_thread_count(1);
  }

  TEST(ElasticBody, ClosestPointAndDofHandler)
  {
    const auto        &body = seed_cube();
    const unsigned int i    = body.closest_point({{0.5, 1.0, 1.0}});
    const auto         X    = body.reference_configuration();
    EXPECT_DOUBLE_EQ(X[3 * i], 0.5);
    EXPECT_DOUBLE_EQ(X[3 * i + 1], 1.0);
    EXPECT_DOUBLE_EQ(X[3 * i + 2], 1.0);
  }
} // namespace
