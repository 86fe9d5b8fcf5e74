#ifndef estep_fem_ball_mesh_h
#define estep_fem_ball_mesh_h

#include <array>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
} // namespace dealii

namespace estep
{
  /**
   * An unstructured tetrahedral mesh of the ball of radius @p radius about @p
   * centre, made with the gmsh library that deal.II links (OpenCASCADE sphere,
   * 3D Delaunay, one thread, fixed options, so the mesh is reproducible for a
   * given gmsh version). The target element size is @p mesh_size times the
   * radius; boundary nodes lie on the sphere. The default 0.3 gives about
   * the reference text's size: 898 tetrahedra and 258 vertices with Debian's
   * gmsh 4.8.4 (0.6: 155 and 64; see doc/contact_system.md).
   *
   * @p tria must be empty. Throws dealii::ExcMessage, in a sentence that
   * names the mesh size and suits a prefix naming the entry, for a mesh size
   * or radius that is not positive, a mesh size that would make more than
   * max_generated_mesh_cells tetrahedra (about 898 (0.3 / mesh_size)^3), or if
   * gmsh fails (with gmsh's message) or produces no tetrahedra; the result
   * passes check_tetrahedral_mesh(). gmsh is initialised and finalised
   * inside (not thread-safe).
   */
  void
  make_ball_mesh(dealii::Triangulation<3, 3> &tria,
                 const double                 mesh_size = 0.3,
                 const double                 radius    = 1.,
                 const std::array<double, 3> &centre    = {{0., 0., 0.}});
} // namespace estep

#endif
