#ifndef estep_fem_meshes_h
#define estep_fem_meshes_h

#include <array>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace estep
{
  /** The most tetrahedra a mesh generator (ball, box, deal.II) is asked to
   * make, estimated before it runs. */
  constexpr double max_generated_mesh_cells = 1e8;

  /**
   * The cube mesh of the spinning-cube example: the box [lower, upper] (the
   * unit cube by default)
   * divided into an n x n x n grid of hexahedra, each split into 24 tetrahedra
   * by split_hexahedra_into_24_tetrahedra(). For n = 8: 12,288 cells and 2,969
   * vertices (729 grid points + 1,728 face centres + 512 hexahedron centres).
   * @p tria must be empty. Throws (dealii::ExcMessage) if n = 0 or the box is
   * empty.
   */
  void
  make_seed_cube_mesh(dealii::Triangulation<3, 3> &tria,
                      const unsigned int           n_subdivisions,
                      const std::array<double, 3> &lower = {{0., 0., 0.}},
                      const std::array<double, 3> &upper = {{1., 1., 1.}});

  /**
   * Split every hexahedron of @p hex_tria (a mesh of hexahedra only, used on
   * its coarsest level) into 24 tetrahedra: a new vertex at the centre of each
   * face (mean of its four vertices; shared by the two hexahedra of an interior
   * face) and one at the centre of each hexahedron (mean of its eight
   * vertices); each tetrahedron is (hexahedron centre, face centre, the two
   * vertices of one edge of that face), ordered to have positive volume.
   * Material ids are inherited, and so are boundary ids (the four triangles
   * of a boundary face take its id); manifolds are not. @p tet_tria
   * must be empty. This differs from deal.II's
   * GridGenerator::convert_hypercube_to_simplex_mesh (which gives 2,457
   * vertices on the 8^3 cube).
   */
  void
  split_hexahedra_into_24_tetrahedra(
    const dealii::Triangulation<3, 3> &hex_tria,
    dealii::Triangulation<3, 3>       &tet_tria);

  /**
   * Renumber the cells of @p tria (a mesh on its coarsest level only) in the
   * order of their centroids along a Hilbert curve (deal.II's
   * Utilities::inverse_Hilbert_space_filling_curve, of the centroids in the
   * smallest cube that holds them, 32 bits per axis; equal indices keep their
   * order). Vertices, vertex order within each cell, material ids and the
   * boundary ids and manifold ids of faces and edges are kept; manifold
   * objects attached to @p tria are not.
   * Runs of consecutive cells are then compact in space, which is what the
   * division of a body's cells among threads and MPI ranks in runs of whole
   * blocks needs (parallel_blocks.h): a mesher's own order (gmsh's, or the
   * coarse cells of a refined deal.II mesh) can make the points of one run
   * touch cells all over the body.
   */
  void
  order_cells_along_hilbert_curve(dealii::Triangulation<3, 3> &tria);

  /**
   * order_cells_along_hilbert_curve() if @p tria has more than one block of
   * cells (block_size of parallel_blocks.h); a mesh of one block, which
   * threads and ranks never divide, keeps its order. What every mesh but the
   * box (made layer by layer) goes through: make_mesh()'s and the colliding
   * balls'.
   */
  void
  order_cells_compactly(dealii::Triangulation<3, 3> &tria);

  /**
   * Check that @p tria is a non-empty mesh of tetrahedra only, each with a
   * positive volume (vertex order as deal.II's reference tetrahedron) larger
   * than 1e-12 times the cube of its longest edge, no two cells with the
   * same vertices and no triangle a face of more than two cells. Throws
   * dealii::ExcMessage naming the first offending cell (index, vertices) or
   * cells otherwise.
   */
  void
  check_tetrahedral_mesh(const dealii::Triangulation<3, 3> &tria);
} // namespace estep

#endif
