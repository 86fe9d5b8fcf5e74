#include <deal.II/grid/tria.h>

#include <estep/contact/boundary_triangles.h>
#include <estep/contact/predicates.h>

#include <stdexcept>
#include <string>

namespace estep
{
  namespace contact
  {
    std::vector<TriangleIndices>
    boundary_triangles(const dealii::Triangulation<3, 3> &triangulation)
    {
      std::vector<TriangleIndices> triangles;
      const auto                   point = [&](const unsigned int i) {
        const dealii::Point<3> &p = triangulation.get_vertices()[i];
        return Point3{{p[0], p[1], p[2]}};
      };
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary())
              continue;
            if (face->n_vertices() != 3)
              throw std::invalid_argument(
                "boundary_triangles: the mesh has a boundary face with " +
                std::to_string(face->n_vertices()) +
                " vertices; only tetrahedral (simplex) meshes are supported");
            TriangleIndices t = {{face->vertex_index(0),
                                  face->vertex_index(1),
                                  face->vertex_index(2)}};
            // The cell's vertex off this face decides the orientation: it must
            // lie below.
            for (const unsigned int v : cell->vertex_indices())
              {
                const unsigned int i = cell->vertex_index(v);
                if (i == t[0] || i == t[1] || i == t[2])
                  continue;
                if (orient3d(point(t[0]), point(t[1]), point(t[2]), point(i)) >
                    0)
                  std::swap(t[1], t[2]);
                break;
              }
            triangles.push_back(t);
          }
      return triangles;
    }
  } // namespace contact
} // namespace estep
