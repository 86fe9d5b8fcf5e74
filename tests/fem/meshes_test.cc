// Meshes: the cube of hexahedra split into 24 tetrahedra, deal.II generators,
// gmsh files, the cells renumbered along a Hilbert curve and the error
// messages for bad input.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace
{
  /** The message of the exception thrown by make_mesh(), or "" if none. */
  std::string
  error_of(const estep::MeshDescription &d)
  {
    dealii::Triangulation<3> tria;
    try
      {
        estep::make_mesh(d, tria);
      }
    catch (const std::exception &e)
      {
        return e.what();
      }
    return "";
  }

  TEST(Meshes, SeedCubeCounts)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, 8);
    EXPECT_EQ(tria.n_active_cells(), 12288u);
    EXPECT_EQ(tria.n_vertices(), 2969u);
    estep::check_tetrahedral_mesh(tria);
    double volume = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      volume += cell->measure();
    EXPECT_NEAR(volume, 1., 1e-12);
  }

  TEST(Meshes, FactoryTypes)
  {
    estep::MeshDescription d;
    {
      dealii::Triangulation<3> tria;
      d.n_subdivisions = 2;
      d.shift          = {{1., 0., 0.}};
      estep::make_mesh(d, tria);
      EXPECT_EQ(tria.n_active_cells(), 8u * 24u);
      EXPECT_EQ(tria.n_vertices(), 27u + 36u + 8u);
    }
    {
      dealii::Triangulation<3> tria;
      d           = estep::MeshDescription();
      d.type      = "deal.II";
      d.generator = "hyper_cube";
      d.arguments = "0 : 1 : false";
      estep::make_mesh(d, tria);
      EXPECT_EQ(tria.n_active_cells(), 24u);
    }
    {
      dealii::Triangulation<3> tria;
      d.type          = "deal.II 24";
      d.generator     = "hyper_ball";
      d.arguments     = "0, 0, 0 : 1 : false";
      d.n_refinements = 0;
      estep::make_mesh(d, tria);
      EXPECT_EQ(tria.n_active_cells(), 7u * 24u);
    }
  }

  TEST(Meshes, Deal24KeepsBoundaryIds)
  {
    // A colorized box: ids 0 to 5 on the faces x = 0, x = 2, y = 0, y = 1,
    // z = 0, z = 1; every boundary triangle of the split mesh has the id of
    // the face it lies in (they were all 0).
    estep::MeshDescription d;
    d.type      = "deal.II 24";
    d.generator = "subdivided_hyper_rectangle";
    d.arguments = "2, 1, 1 : 0, 0, 0 : 2, 1, 1 : true";
    dealii::Triangulation<3> tria;
    estep::make_mesh(d, tria);
    const double                         upper[3] = {2., 1., 1.};
    std::map<unsigned int, unsigned int> triangles_with_id;
    for (const auto &cell : tria.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            const dealii::Point<3> c        = face->center();
            unsigned int           expected = 99;
            for (unsigned int axis = 0; axis < 3; ++axis)
              if (std::abs(c[axis]) < 1e-12)
                expected = 2 * axis;
              else if (std::abs(c[axis] - upper[axis]) < 1e-12)
                expected = 2 * axis + 1;
            EXPECT_EQ(face->boundary_id(), expected) << "face at " << c;
            ++triangles_with_id[face->boundary_id()];
          }
    // 4 triangles per quadrilateral: 1 on each end, 2 on each long side.
    const std::map<unsigned int, unsigned int> expected_counts = {
      {0, 4}, {1, 4}, {2, 8}, {3, 8}, {4, 8}, {5, 8}};
    EXPECT_EQ(triangles_with_id, expected_counts);
  }

  /** Each cell's vertices (in its own order) and material id, or each
   * boundary face's vertices (sorted) and boundary id, as numbers, sorted:
   * the mesh whatever the order of its cells and vertices. */
  std::vector<std::vector<double>>
  cells_of(const dealii::Triangulation<3> &tria, const bool boundary)
  {
    std::vector<std::vector<double>> all;
    for (const auto &cell : tria.active_cell_iterators())
      if (!boundary)
        {
          std::vector<double> numbers{double(cell->material_id())};
          for (unsigned int v = 0; v < 4; ++v)
            for (unsigned int c = 0; c < 3; ++c)
              numbers.push_back(cell->vertex(v)[c]);
          all.push_back(numbers);
        }
      else
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              std::vector<std::array<double, 3>> points;
              for (unsigned int v = 0; v < 3; ++v)
                points.push_back({{face->vertex(v)[0],
                                   face->vertex(v)[1],
                                   face->vertex(v)[2]}});
              std::sort(points.begin(), points.end());
              std::vector<double> numbers{double(face->boundary_id())};
              for (const auto &p : points)
                numbers.insert(numbers.end(), p.begin(), p.end());
              all.push_back(numbers);
            }
    std::sort(all.begin(), all.end());
    return all;
  }

  TEST(Meshes, HilbertOrderKeepsTheMesh)
  {
    // A cube with boundary ids 0 to 5 on its sides, refined twice: 1,536
    // tetrahedra, more than one block, so make_mesh() renumbers them.
    estep::MeshDescription d;
    d.type          = "deal.II";
    d.generator     = "hyper_cube";
    d.arguments     = "0 : 1 : true";
    d.n_refinements = 2;
    dealii::Triangulation<3> ordered;
    estep::make_mesh(d, ordered);
    dealii::Triangulation<3> hex, plain;
    dealii::GridGenerator::hyper_cube(hex, 0., 1., true);
    hex.refine_global(2);
    dealii::GridGenerator::convert_hypercube_to_simplex_mesh(hex, plain);
    ASSERT_EQ(ordered.n_active_cells(), 1536u);
    ASSERT_EQ(plain.n_active_cells(), 1536u);
    EXPECT_EQ(cells_of(ordered, false), cells_of(plain, false));
    const std::vector<std::vector<double>> faces = cells_of(ordered, true);
    EXPECT_EQ(faces, cells_of(plain, true));
    EXPECT_EQ(faces.size(), 6u * 16u * 4u);
    EXPECT_EQ(faces.back()[0], 5.);
    // The order did change: the first cells lie in one corner, not in each
    // coarse child of deal.II's order.
    unsigned int moved = 0;
    auto         p     = plain.begin_active();
    for (const auto &cell : ordered.active_cell_iterators())
      moved += cell->center().distance((p++)->center()) > 1e-12;
    EXPECT_GT(moved, 1000u);
    estep::check_tetrahedral_mesh(ordered);
  }

  TEST(Meshes, Gmsh)
  {
    // Two tetrahedra sharing a face (gmsh format 2).
    const std::string name = "fem_meshes_test_two_tets.msh";
    {
      std::ofstream out(name);
      out
        << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n"
        << "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n"
        << "$Elements\n2\n1 4 2 0 1 1 2 3 4\n2 4 2 0 1 2 3 4 5\n$EndElements\n";
    }
    estep::MeshDescription d;
    d.type      = "gmsh";
    d.file_name = name;
    dealii::Triangulation<3> tria;
    estep::make_mesh(d, tria);
    EXPECT_EQ(tria.n_active_cells(), 2u);
    EXPECT_EQ(tria.n_vertices(), 5u);

    // deal.II's GridIn reorients a negatively numbered tetrahedron: accepted.
    {
      std::ofstream out(name);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n"
          << "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
          << "$Elements\n1\n1 4 2 0 1 1 3 2 4\n$EndElements\n";
    }
    EXPECT_EQ(error_of(d), "");

    // A flat (degenerate) element is rejected with a clear message.
    {
      std::ofstream out(name);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n"
          << "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n$EndNodes\n"
          << "$Elements\n1\n1 4 2 0 1 1 2 3 4\n$EndElements\n";
    }
    EXPECT_NE(error_of(d).find("degenerate tetrahedron"), std::string::npos)
      << error_of(d);

    // A cell listed twice: deal.II accepts it, and the two copies hide each
    // other's faces from the boundary.
    {
      std::ofstream out(name);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n"
          << "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n$EndNodes\n"
          << "$Elements\n3\n1 4 2 0 1 1 2 3 4\n2 4 2 0 1 2 3 4 5\n"
          << "3 4 2 0 1 1 2 3 4\n$EndElements\n";
    }
    EXPECT_NE(error_of(d).find(
                "two cells with the same vertices (cells 0 and 2)"),
              std::string::npos)
      << error_of(d);

    // Three distinct cells on one triangle (0, 1, 2): not a manifold.
    {
      std::ofstream out(name);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n"
          << "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 0 0 -1\n6 0.2 0.2 2\n"
          << "$EndNodes\n$Elements\n3\n1 4 2 0 1 1 2 3 4\n"
          << "2 4 2 0 1 1 3 2 5\n3 4 2 0 1 1 2 3 6\n$EndElements\n";
    }
    EXPECT_NE(error_of(d).find("more than two cells (cells 0, 1 and 2)"),
              std::string::npos)
      << error_of(d);

    // Garbage.
    {
      std::ofstream out(name);
      out << "this is not a mesh\n";
    }
    EXPECT_NE(error_of(d).find("cannot read the gmsh file"), std::string::npos)
      << error_of(d);
    std::remove(name.c_str());

    d.file_name = "no_such_file.msh";
    EXPECT_NE(error_of(d).find("cannot open the gmsh file 'no_such_file.msh'"),
              std::string::npos)
      << error_of(d);

    d.file_name = "a_directory.msh";
    std::filesystem::create_directory(d.file_name);
    EXPECT_NE(error_of(d).find(
                "the gmsh file 'a_directory.msh' is a directory, not a file."),
              std::string::npos)
      << error_of(d);
    std::filesystem::remove(d.file_name);
  }

  TEST(Meshes, BadDescriptions)
  {
    estep::MeshDescription d;
    d.type = "sphere";
    EXPECT_NE(error_of(d).find("unknown type 'sphere'"), std::string::npos);
    d           = estep::MeshDescription();
    d.type      = "deal.II";
    d.generator = "no_such_generator";
    EXPECT_NE(error_of(d).find("generator 'no_such_generator'"),
              std::string::npos)
      << error_of(d);
    d                = estep::MeshDescription();
    d.n_subdivisions = 0;
    EXPECT_NE(error_of(d).find("subdivisions"), std::string::npos)
      << error_of(d);
    // Too many tetrahedra for a generator: refused before it runs (160 is
    // the largest box, 24 * 160^3 = 98,304,000 tetrahedra).
    d.n_subdivisions = 161;
    EXPECT_NE(error_of(d).find("Subdivisions must be at most 160"),
              std::string::npos)
      << error_of(d);
    d               = estep::MeshDescription();
    d.type          = "deal.II 24";
    d.generator     = "hyper_cube";
    d.arguments     = "0 : 1 : false";
    d.n_refinements = 9;
    EXPECT_NE(error_of(d).find("with 9 refinements would make"),
              std::string::npos)
      << error_of(d);
  }

  TEST(Meshes, Parameters)
  {
    dealii::ParameterHandler prm;
    estep::MeshDescription::declare_parameters(prm);
    prm.parse_input_from_string(
      "set Type = box\nset Subdivisions = 3\n"
      "set Upper corner = 2, 1, 1\nset Shift = 0, 0, 5\n");
    estep::MeshDescription d;
    d.parse_parameters(prm);
    EXPECT_EQ(d.n_subdivisions, 3u);
    EXPECT_EQ(d.upper[0], 2.);
    EXPECT_EQ(d.shift[2], 5.);
    dealii::Triangulation<3> tria;
    estep::make_mesh(d, tria);
    EXPECT_EQ(tria.n_active_cells(), 27u * 24u);
  }
} // namespace
