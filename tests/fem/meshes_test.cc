// Meshes: the cube of hexahedra split into 24 tetrahedra, deal.II generators,
// gmsh files and the error messages for bad input.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

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
