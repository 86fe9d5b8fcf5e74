#ifndef estep_contact_boundary_triangles_h
#define estep_contact_boundary_triangles_h

#include <estep/contact/bounding_volume_hierarchy.h>

#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
} // namespace dealii

namespace estep
{
  namespace contact
  {
    /**
     * The boundary triangles of a tetrahedral mesh (a deal.II simplex
     * triangulation, e.g. from
     * GridGenerator::subdivided_hyper_cube_with_simplices()), as triples of the
     * triangulation's vertex indices, oriented so that (b - a) x (c - a) points
     * out of the body. The contact classes expect point i of the coordinate
     * vector q to be vertex i of this numbering: remap the indices if the
     * finite-element numbering differs.
     *
     * Throws std::invalid_argument if a boundary face is not a triangle.
     */
    std::vector<TriangleIndices>
    boundary_triangles(const dealii::Triangulation<3, 3> &triangulation);
  } // namespace contact
} // namespace estep

#endif
