#ifndef estep_composite_static_surface_h
#define estep_composite_static_surface_h

#include <estep/contact/geometry.h>

#include <string>
#include <vector>

namespace estep
{
  /**
   * A rigid obstacle given as a fixed triangle surface: its points and its
   * triangles, as ContactSystem takes them (see its constructor with
   * surfaces). The surface need not be closed, oriented or connected; it
   * is a set of triangles that the bodies may touch from either side and
   * never cross.
   */
  struct StaticSurface
  {
    /** The coordinates of the points, three per point (x, y, z). */
    std::vector<double> points;

    /** The triangles, as indices into the points (three distinct points
     * each). */
    std::vector<contact::TriangleIndices> triangles;

    /** A name for messages (the file it was read from). */
    std::string name;

    /** Number of points. */
    unsigned int
    n_points() const;

    /** Throws std::runtime_error naming the surface if it has no triangle,
     * a coordinate is not finite, or a triangle refers to a missing point
     * or repeats a point. */
    void
    check() const;
  };

  /**
   * The triangles of an STL file, ASCII ("solid ... facet normal ... outer
   * loop vertex x y z ... endloop endfacet ... endsolid") or binary (an
   * 80-byte header, the number of triangles, and 50 bytes for each: normal,
   * three vertices in single precision, attributes). A file is read as
   * binary if its size is 84 bytes plus 50 for each triangle its bytes 80 to
   * 83 count, whatever its header begins with (exporters often write "solid"
   * there); otherwise as ASCII. Facet normals and attributes are not used.
   * Vertices with identical coordinates (exactly) become one point, numbered
   * in the order of their first appearance. Throws std::runtime_error naming
   * the file if it cannot be read, is neither, has a loop of other than
   * three vertices, or has no facet (see StaticSurface::check()).
   */
  StaticSurface
  read_stl_surface(const std::string &filename);

  /**
   * The triangles of a gmsh surface mesh (.msh, formats 2 and 4 that
   * deal.II's GridIn<2, 3>::read_msh() reads, once check_gmsh_file() has
   * found it safe to), read through a dealii::Triangulation<2, 3>; the
   * points are the triangulation's used
   * vertices in their order. Throws std::runtime_error naming the file if
   * it cannot be read, has no triangle or has elements that are not
   * triangles.
   */
  StaticSurface
  read_msh_surface(const std::string &filename);

  /** read_stl_surface() or read_msh_surface() after the extension of
   * @p filename (".stl" or ".msh", any case); a std::runtime_error naming
   * the file for any other extension. */
  StaticSurface
  read_static_surface(const std::string &filename);
} // namespace estep

#endif
