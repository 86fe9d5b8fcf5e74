#ifndef estep_io_vtu_file_h
#define estep_io_vtu_file_h

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace estep
{
  /**
   * VTK XML unstructured-grid files (.vtu, read by ParaView and VisIt) of one
   * tetrahedral mesh with shared vertices, written straight from arrays.
   *
   * Every array is stored as zlib-compressed binary (VTK's
   * vtkZLibDataCompressor, one block, UInt32 header, inline base64), the
   * fields and points as Float32 like deal.II's DataOut. Unlike DataOut, which
   * writes each cell as its own patch with four private vertices, vertex
   * fields are stored once per vertex and cell fields once per cell: for the
   * spinning cube (n = 8) a snapshot holds 2,969 points instead of 49,152. The
   * points and cells do not change between snapshots and are encoded once, in
   * the constructor.
   */
  class VtuFile
  {
  public:
    /** A field: @p n_components values per point or cell, point- or
     * cell-major. */
    struct Field
    {
      std::string                name;
      unsigned int               n_components;
      const std::vector<double> *values;
    };

    /**
     * The mesh: @p points holds x, y, z of each point; @p tetrahedra the
     * point indices of each cell, @p points_per_cell of them (4: tetrahedra;
     * 3: triangles, for surfaces).
     */
    VtuFile(const std::vector<double>       &points,
            const std::vector<unsigned int> &tetrahedra,
            const unsigned int               points_per_cell = 4);

    /**
     * Writes one file: the mesh with the given point and cell fields, and the
     * time and cycle as field data (TIME, CYCLE). As the other writers, it
     * leaves a failure in the state of @p out for the caller, who knows the
     * file's name, to report.
     */
    void
    write(std::ostream             &out,
          const double              time,
          const unsigned int        cycle,
          const std::vector<Field> &point_fields,
          const std::vector<Field> &cell_fields) const;

    /**
     * Writes the .pvtu file of a mesh written in @p pieces (.vtu files of
     * write(), named relative to it) with fields named and sized as
     * @p point_fields and @p cell_fields (their values are not read).
     */
    static void
    write_parallel(std::ostream                   &out,
                   const std::vector<std::string> &pieces,
                   const std::vector<Field>       &point_fields,
                   const std::vector<Field>       &cell_fields);

    /** Writes the .pvd file (a VTK collection, ParaView's time series) of
     * the @p snapshots: the time and the file of each. */
    static void
    write_series(std::ostream                                      &out,
                 const std::vector<std::pair<double, std::string>> &snapshots);

    /** The bytes of a data array compressed in one zlib block. */
    static constexpr unsigned int compression_block_size = 1u << 16;

    /** The encoding of a data array: zlib (level 1) in blocks of
     * compression_block_size bytes, compressed side by side on the threads,
     * and base64, with VTK's block header. */
    static std::string
    encode(const void *data, const std::size_t n_bytes);

  private:
    unsigned int n_points;
    unsigned int n_cells;
    std::string  encoded_points;
    std::string  encoded_connectivity;
    std::string  encoded_offsets;
    std::string  encoded_types;
  };
} // namespace estep

#endif
