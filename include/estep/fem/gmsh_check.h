#ifndef estep_fem_gmsh_check_h
#define estep_fem_gmsh_check_h

#include <string>

namespace estep
{
  /**
   * Check that the gmsh file @p filename (formats 1, 2 and 4 in ASCII) is one
   * that deal.II 9.4's GridIn<dim, 3>::read_msh(std::istream &) reads safely,
   * before it is given to it. That reader trusts its input: in a Release
   * build its checks of the format version, of the node count of the blocks
   * of format 4, of the entity dimensions and of the nodes of boundary faces
   * are Asserts, which do nothing, and it loops on counts whatever the
   * stream's state. A malformed file (found by tests/fuzz/msh_fuzzer.cc)
   * could thus write past its arrays, allocate gigabytes for a count, or loop
   * without end.
   *
   * This function follows the file as read_msh() reads it, token by token,
   * and requires: a version of 1, 2.0 to 2.2, 4.0 or 4.1, ASCII with 8-byte
   * doubles; every number where read_msh() reads one, whole and in the range
   * of its type (unsigned where read_msh() reads an unsigned, finite
   * coordinates); every section and block count matched by what follows, the
   * nodes of the blocks adding up to the announced count; entity dimensions
   * 0 to 3; at most one physical tag per entity; every node that an element
   * names defined; element types that read_msh() knows for @p dim (points,
   * lines, triangles, quadrilaterals, and for dim = 3 tetrahedra and
   * hexahedra) with the node count it expects; the closing line of every
   * section it reads. Throws a std::runtime_error naming the line otherwise.
   * @p dim: 3 for a body's mesh, 2 for a surface.
   */
  void
  check_gmsh_file(const std::string &filename, const unsigned int dim);
} // namespace estep

#endif
