#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <estep/base/parallel_blocks.h>
#include <estep/fem/meshes.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>
#include <vector>

namespace estep
{
  namespace
  {
    /** Six times the signed volume of the tetrahedron (x0, x1, x2, x3). */
    double
    six_volume(const dealii::Point<3> &x0,
               const dealii::Point<3> &x1,
               const dealii::Point<3> &x2,
               const dealii::Point<3> &x3)
    {
      const dealii::Tensor<1, 3> a = x1 - x0, b = x2 - x0, c = x3 - x0;
      return a[0] * (b[1] * c[2] - b[2] * c[1]) -
             a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
  } // namespace

  void
  split_hexahedra_into_24_tetrahedra(
    const dealii::Triangulation<3, 3> &hex_tria,
    dealii::Triangulation<3, 3>       &tet_tria)
  {
    AssertThrow(
      hex_tria.n_levels() > 0 && hex_tria.n_cells(0) > 0,
      dealii::ExcMessage(
        "split_hexahedra_into_24_tetrahedra: the input mesh is empty."));
    AssertThrow(
      tet_tria.n_levels() == 0,
      dealii::ExcMessage(
        "split_hexahedra_into_24_tetrahedra: the output mesh must be empty."));

    // Keep the vertices of the input (unused ones are simply not referenced).
    std::vector<dealii::Point<3>> vertices = hex_tria.get_vertices();
    std::map<unsigned int, unsigned int>
                                     face_centre; // face index -> new vertex
    std::vector<dealii::CellData<3>> cells;
    cells.reserve(24 * hex_tria.n_cells(0));
    // The four triangles of a boundary face take its boundary id (0, the
    // default, need not be listed).
    dealii::SubCellData boundary;

    // Vertex pairs forming the four edges of a quadrilateral face (deal.II's
    // lexicographic face vertex numbering: the cycle is 0-1-3-2).
    static const unsigned int face_edges[4][2] = {{0, 1},
                                                  {1, 3},
                                                  {3, 2},
                                                  {2, 0}};

    for (const auto &cell : hex_tria.cell_iterators_on_level(0))
      {
        AssertThrow(
          cell->reference_cell() == dealii::ReferenceCells::Hexahedron,
          dealii::ExcMessage("split_hexahedra_into_24_tetrahedra: cell " +
                             std::to_string(cell->index()) +
                             " of the input mesh is not a hexahedron."));
        dealii::Point<3> centre;
        for (unsigned int v = 0; v < 8; ++v)
          centre += cell->vertex(v);
        centre /= 8.;
        const unsigned int centre_index = vertices.size();
        vertices.push_back(centre);

        for (unsigned int f = 0; f < 6; ++f)
          {
            const auto face = cell->face(f);
            auto       it   = face_centre.find(face->index());
            if (it == face_centre.end())
              {
                dealii::Point<3> c;
                for (unsigned int v = 0; v < 4; ++v)
                  c += face->vertex(v);
                c /= 4.;
                it = face_centre.emplace(face->index(), vertices.size()).first;
                vertices.push_back(c);
              }
            for (const auto &edge : face_edges)
              {
                dealii::CellData<3> tet(4);
                tet.vertices[0] = centre_index;
                tet.vertices[1] = it->second;
                tet.vertices[2] = face->vertex_index(edge[0]);
                tet.vertices[3] = face->vertex_index(edge[1]);
                if (six_volume(vertices[tet.vertices[0]],
                               vertices[tet.vertices[1]],
                               vertices[tet.vertices[2]],
                               vertices[tet.vertices[3]]) < 0.)
                  std::swap(tet.vertices[2], tet.vertices[3]);
                tet.material_id = cell->material_id();
                cells.push_back(tet);
                if (face->at_boundary() && face->boundary_id() != 0)
                  {
                    dealii::CellData<2> triangle(3);
                    triangle.vertices    = {it->second,
                                            face->vertex_index(edge[0]),
                                            face->vertex_index(edge[1])};
                    triangle.boundary_id = face->boundary_id();
                    boundary.boundary_quads.push_back(triangle);
                  }
              }
          }
      }
    tet_tria.create_triangulation(vertices, cells, boundary);
  }

  void
  make_seed_cube_mesh(dealii::Triangulation<3, 3> &tria,
                      const unsigned int           n_subdivisions,
                      const std::array<double, 3> &lower,
                      const std::array<double, 3> &upper)
  {
    AssertThrow(n_subdivisions > 0,
                dealii::ExcMessage(
                  "the number of subdivisions must be positive."));
    for (unsigned int d = 0; d < 3; ++d)
      AssertThrow(upper[d] > lower[d],
                  dealii::ExcMessage(
                    "the box is empty (its upper corner is not above its "
                    "lower corner in every direction)."));
    dealii::Triangulation<3, 3> hex;
    dealii::GridGenerator::subdivided_hyper_rectangle(
      hex,
      std::vector<unsigned int>(3, n_subdivisions),
      dealii::Point<3>(lower[0], lower[1], lower[2]),
      dealii::Point<3>(upper[0], upper[1], upper[2]));
    split_hexahedra_into_24_tetrahedra(hex, tria);
  }

  namespace
  {
    /**
     * Throws unless no two cells have the same four vertices and no
     * triangle is a face of more than two cells (deal.II accepts both; a cell
     * listed twice hides its faces from the boundary, so contact would not
     * see them).
     */
    void
    check_cells_are_distinct_and_faces_shared_by_two(
      const dealii::Triangulation<3, 3> &tria)
    {
      using Vertices = std::array<unsigned int, 4>;
      std::vector<std::pair<Vertices, unsigned int>>                    cells;
      std::vector<std::pair<std::array<unsigned int, 3>, unsigned int>> faces;
      for (const auto &cell : tria.active_cell_iterators())
        {
          Vertices v;
          for (unsigned int i = 0; i < 4; ++i)
            v[i] = cell->vertex_index(i);
          std::sort(v.begin(), v.end());
          const unsigned int c = cell->active_cell_index();
          cells.emplace_back(v, c);
          for (unsigned int skipped = 0; skipped < 4; ++skipped)
            {
              std::array<unsigned int, 3> f;
              for (unsigned int i = 0, j = 0; i < 4; ++i)
                if (i != skipped)
                  f[j++] = v[i];
              faces.emplace_back(f, c);
            }
        }
      std::sort(cells.begin(), cells.end());
      for (std::size_t i = 1; i < cells.size(); ++i)
        AssertThrow(cells[i].first != cells[i - 1].first,
                    dealii::ExcMessage(
                      "The mesh has two cells with the same vertices (cells " +
                      std::to_string(cells[i - 1].second) + " and " +
                      std::to_string(cells[i].second) +
                      "): a cell is listed twice."));
      std::sort(faces.begin(), faces.end());
      for (std::size_t i = 2; i < faces.size(); ++i)
        AssertThrow(faces[i].first != faces[i - 2].first,
                    dealii::ExcMessage(
                      "The mesh is not a manifold: the triangle of vertices " +
                      std::to_string(faces[i].first[0]) + ", " +
                      std::to_string(faces[i].first[1]) + ", " +
                      std::to_string(faces[i].first[2]) +
                      " is a face of more than two cells (cells " +
                      std::to_string(faces[i - 2].second) + ", " +
                      std::to_string(faces[i - 1].second) + " and " +
                      std::to_string(faces[i].second) + ")."));
    }
  } // namespace

  void
  check_tetrahedral_mesh(const dealii::Triangulation<3, 3> &tria)
  {
    AssertThrow(tria.n_active_cells() > 0,
                dealii::ExcMessage("The mesh has no cells."));
    for (const auto &cell : tria.active_cell_iterators())
      {
        AssertThrow(cell->reference_cell() ==
                      dealii::ReferenceCells::Tetrahedron,
                    dealii::ExcMessage(
                      "The mesh has a cell that is not a tetrahedron (cell " +
                      std::to_string(cell->active_cell_index()) +
                      "); the elastic body needs a mesh of tetrahedra only "
                      "(convert hexahedral meshes first)."));
        double longest = 0.;
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int j = i + 1; j < 4; ++j)
            longest =
              std::max(longest, cell->vertex(i).distance(cell->vertex(j)));
        const double v6 = six_volume(cell->vertex(0),
                                     cell->vertex(1),
                                     cell->vertex(2),
                                     cell->vertex(3));
        if (!(v6 > 6e-12 * longest * longest * longest))
          {
            std::ostringstream message;
            message << "The mesh has "
                    << (v6 < 0. ? "an inverted" : "a degenerate")
                    << " tetrahedron: cell " << cell->active_cell_index()
                    << " has signed volume " << v6 / 6. << " (vertices";
            for (unsigned int i = 0; i < 4; ++i)
              message << " (" << cell->vertex(i) << ")";
            message
              << "). Tetrahedra must have positive volume in deal.II's vertex order.";
            AssertThrow(false, dealii::ExcMessage(message.str()));
          }
      }
    check_cells_are_distinct_and_faces_shared_by_two(tria);
  }

  void
  order_cells_along_hilbert_curve(dealii::Triangulation<3, 3> &tria)
  {
    AssertThrow(tria.n_levels() == 1,
                dealii::ExcMessage("order_cells_along_hilbert_curve: the mesh "
                                   "must not be refined."));
    auto [vertices, cells, faces_and_edges] =
      dealii::GridTools::get_coarse_mesh_description(tria);
    std::vector<dealii::Point<3>> centroids;
    centroids.reserve(cells.size());
    for (const dealii::CellData<3> &cell : cells)
      {
        dealii::Point<3> sum;
        for (const unsigned int v : cell.vertices)
          sum += vertices[v];
        centroids.push_back(sum / double(cell.vertices.size()));
      }
    // Integer coordinates on one scale for all three axes: deal.II's
    // version for points scales each axis to its own extent, which cuts a
    // long body into runs across its length.
    dealii::Point<3> lower = centroids[0], upper = centroids[0];
    for (const dealii::Point<3> &c : centroids)
      for (unsigned int d = 0; d < 3; ++d)
        {
          lower[d] = std::min(lower[d], c[d]);
          upper[d] = std::max(upper[d], c[d]);
        }
    double extent = 0.;
    for (unsigned int d = 0; d < 3; ++d)
      extent = std::max(extent, upper[d] - lower[d]);
    constexpr int bits    = 32;
    const double  largest = std::ldexp(1., bits) - 1.;
    const double  scale   = extent > 0. ? largest / extent : 0.;
    std::vector<std::array<std::uint64_t, 3>> coordinates(centroids.size());
    for (std::size_t e = 0; e < centroids.size(); ++e)
      for (unsigned int d = 0; d < 3; ++d)
        coordinates[e][d] = static_cast<std::uint64_t>(
          std::min((centroids[e][d] - lower[d]) * scale, largest));
    const std::vector<std::array<std::uint64_t, 3>> curve =
      dealii::Utilities::inverse_Hilbert_space_filling_curve<3>(coordinates,
                                                                bits);
    std::vector<unsigned int> order(cells.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(),
                     order.end(),
                     [&](const unsigned int a, const unsigned int b) {
                       return curve[a] < curve[b];
                     });
    std::vector<dealii::CellData<3>> ordered;
    ordered.reserve(cells.size());
    for (const unsigned int e : order)
      ordered.push_back(cells[e]);
    tria.clear();
    tria.create_triangulation(vertices, ordered, faces_and_edges);
  }

  void
  order_cells_compactly(dealii::Triangulation<3, 3> &tria)
  {
    if (tria.n_active_cells() > block_size)
      order_cells_along_hilbert_curve(tria);
  }
} // namespace estep
