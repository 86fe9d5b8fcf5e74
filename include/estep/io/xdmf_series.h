#ifndef estep_io_xdmf_series_h
#define estep_io_xdmf_series_h

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace estep
{
  /**
   * The XDMF file (version 2, read by ParaView and VisIt) of a time series of
   * HDF5 snapshots of meshes whose points and cells do not change: the meshes
   * are in one HDF5 file, each snapshot's fields in its own.
   */
  struct XdmfSeries
  {
    /** A mesh: the group that holds its datasets "points" (x, y, z per
     * point) and "cells" (the point indices of each cell) in the mesh file,
     * and in every snapshot file its fields, unless it has none. */
    struct Mesh
    {
      std::string  name;
      std::string  group;
      std::size_t  n_points;
      std::size_t  n_cells;
      unsigned int points_per_cell; // 4: tetrahedra, 3: triangles
      bool         has_fields;
    };

    /** A field of every mesh that has fields: 1 (scalar), 3 (vector) or 9
     * (tensor) components per point or per cell. */
    struct Field
    {
      std::string  name;
      unsigned int n_components;
      bool         on_cells;
    };

    /** The HDF5 file of the meshes, relative to the XDMF file. */
    std::string        mesh_file;
    std::vector<Mesh>  meshes;
    std::vector<Field> fields;

    /**
     * The text of the XDMF file listing the @p snapshots: the time and the
     * HDF5 file (relative to the XDMF file) of each. One mesh is one grid
     * per time; several are a spatial collection (a multiblock data set).
     */
    std::string
    text(const std::vector<std::pair<double, std::string>> &snapshots) const;
  };
} // namespace estep

#endif
