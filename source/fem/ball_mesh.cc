#include <deal.II/base/config.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <estep/base/exception_text.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/meshes.h>

#ifdef DEAL_II_GMSH_WITH_API
#  include <gmsh.h>
#endif

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace estep
{
  namespace
  {
    /** @p x with six significant digits. */
    std::string
    short_number(const double x)
    {
      std::ostringstream text;
      text << x;
      return text.str();
    }

    [[maybe_unused]] std::string
    gmsh_failed(const double mesh_size)
    {
      return "gmsh could not mesh a ball with the mesh size " +
             short_number(mesh_size) + " (relative to the radius)";
    }
  } // namespace



  void
  make_ball_mesh(dealii::Triangulation<3, 3> &tria,
                 const double                 mesh_size,
                 const double                 radius,
                 const std::array<double, 3> &centre)
  {
    AssertThrow(mesh_size > 0. && radius > 0.,
                dealii::ExcMessage(
                  "the mesh size and the radius of a ball must be positive."));
    // 898 tetrahedra at 0.3, and as many more as the volume of one shrinks.
    const double estimated_cells = 898. * std::pow(0.3 / mesh_size, 3);
    AssertThrow(
      estimated_cells <= max_generated_mesh_cells,
      dealii::ExcMessage(
        "the mesh size " + short_number(mesh_size) +
        " (relative to the radius) would make a ball of about " +
        short_number(estimated_cells) + " tetrahedra, more than " +
        short_number(max_generated_mesh_cells) + "; it must be at least " +
        short_number(0.3 * std::cbrt(898. / max_generated_mesh_cells)) + "."));
    AssertThrow(tria.n_cells() == 0,
                dealii::ExcMessage("make_ball_mesh: the mesh must be empty."));
#ifndef DEAL_II_GMSH_WITH_API
    AssertThrow(
      false,
      dealii::ExcMessage(
        "make_ball_mesh needs deal.II configured with the gmsh API."));
#else
    std::vector<dealii::Point<3>>    vertices;
    std::vector<dealii::CellData<3>> cells;
    try
      {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.NumThreads", 1);
        gmsh::option::setNumber("Mesh.Algorithm", 6);
        gmsh::option::setNumber("Mesh.Algorithm3D", 1);
        gmsh::option::setNumber("Mesh.RandomSeed", 1);
        gmsh::option::setNumber("Mesh.MeshSizeMin", mesh_size);
        gmsh::option::setNumber("Mesh.MeshSizeMax", mesh_size);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        gmsh::option::setNumber("Mesh.Optimize", 1);
        gmsh::model::add("ball");
        gmsh::model::occ::addSphere(0., 0., 0., 1.);
        gmsh::model::occ::synchronize();
        gmsh::model::mesh::generate(3);

        std::vector<std::size_t> node_tags;
        std::vector<double>      coordinates, parametric;
        gmsh::model::mesh::getNodes(node_tags, coordinates, parametric);
        std::vector<int>                      types;
        std::vector<std::vector<std::size_t>> element_tags, element_nodes;
        gmsh::model::mesh::getElements(types, element_tags, element_nodes, 3);
        gmsh::finalize();

        // Only the nodes used by tetrahedra, numbered in order of appearance.
        std::map<std::size_t, unsigned int> index;
        std::map<std::size_t, std::size_t>  position;
        for (std::size_t i = 0; i < node_tags.size(); ++i)
          position[node_tags[i]] = i;
        for (unsigned int k = 0; k < types.size(); ++k)
          {
            if (types[k] != 4) // 4-node tetrahedra
              continue;
            const auto &nodes = element_nodes[k];
            for (std::size_t e = 0; e + 3 < nodes.size(); e += 4)
              {
                dealii::CellData<3> cell(4);
                for (unsigned int v = 0; v < 4; ++v)
                  {
                    const std::size_t tag = nodes[e + v];
                    auto              it  = index.find(tag);
                    if (it == index.end())
                      {
                        it = index.emplace(tag, vertices.size()).first;
                        const std::size_t p = position.at(tag);
                        vertices.emplace_back(coordinates[3 * p],
                                              coordinates[3 * p + 1],
                                              coordinates[3 * p + 2]);
                      }
                    cell.vertices[v] = it->second;
                  }
                cells.push_back(cell);
              }
          }
      }
    catch (const std::exception &e)
      {
        AssertThrow(false,
                    dealii::ExcMessage(gmsh_failed(mesh_size) + ": " +
                                       one_line_message(e)));
      }
    catch (const std::string &e)
      {
        // The gmsh API throws its last error message as a string.
        AssertThrow(false,
                    dealii::ExcMessage(gmsh_failed(mesh_size) + ": " + e));
      }
    catch (...)
      {
        AssertThrow(false, dealii::ExcMessage(gmsh_failed(mesh_size) + "."));
      }
    AssertThrow(!cells.empty(),
                dealii::ExcMessage(gmsh_failed(mesh_size) +
                                   ": it made no tetrahedra."));

    // Orient every tetrahedron positively (deal.II's reference vertex order).
    for (auto &cell : cells)
      {
        const auto  &x0  = vertices[cell.vertices[0]];
        const auto   a   = vertices[cell.vertices[1]] - x0;
        const auto   b   = vertices[cell.vertices[2]] - x0;
        const auto   c   = vertices[cell.vertices[3]] - x0;
        const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) -
                           a[1] * (b[0] * c[2] - b[2] * c[0]) +
                           a[2] * (b[0] * c[1] - b[1] * c[0]);
        if (det < 0.)
          std::swap(cell.vertices[1], cell.vertices[2]);
      }
    // Exactly on the sphere where gmsh put the node on it (to round-off), then
    // scaled and shifted.
    for (auto &x : vertices)
      {
        const double r = x.norm();
        if (std::abs(r - 1.) < 1e-8)
          x /= r;
        for (unsigned int c = 0; c < 3; ++c)
          x[c] = centre[c] + radius * x[c];
      }
    tria.create_triangulation(vertices, cells, dealii::SubCellData());
    check_tetrahedral_mesh(tria);
#endif
  }
} // namespace estep
