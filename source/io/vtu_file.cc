#include <estep/base/parallel_blocks.h>
#include <estep/io/vtu_file.h>

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace
  {
    /** Appends the base64 encoding (RFC 4648, with padding) of @p n bytes. */
    void
    append_base64(const unsigned char *bytes,
                  const std::size_t    n,
                  std::string         &out)
    {
      static const char alphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      out.reserve(out.size() + 4 * ((n + 2) / 3));
      std::size_t i = 0;
      for (; i + 3 <= n; i += 3)
        {
          const std::uint32_t group = (std::uint32_t(bytes[i]) << 16) |
                                      (std::uint32_t(bytes[i + 1]) << 8) |
                                      bytes[i + 2];
          out += alphabet[(group >> 18) & 63];
          out += alphabet[(group >> 12) & 63];
          out += alphabet[(group >> 6) & 63];
          out += alphabet[group & 63];
        }
      if (i < n)
        {
          const std::uint32_t group =
            (std::uint32_t(bytes[i]) << 16) |
            (i + 1 < n ? std::uint32_t(bytes[i + 1]) << 8 : 0);
          out += alphabet[(group >> 18) & 63];
          out += alphabet[(group >> 12) & 63];
          out += (i + 1 < n) ? alphabet[(group >> 6) & 63] : '=';
          out += '=';
        }
    }

    /** The values of @p what as Float32, converted; a finite value beyond
     * its range (a blow-up) is an error rather than an undefined conversion.
     */
    std::vector<float>
    as_float(const std::vector<double> &values, const std::string &what)
    {
      std::vector<float> converted(values.size());
      for (std::size_t i = 0; i < values.size(); ++i)
        {
          if (std::isfinite(values[i]) &&
              std::abs(values[i]) > std::numeric_limits<float>::max())
            throw std::range_error(
              "VtuFile: " + what + " has the value " +
              std::to_string(values[i]) +
              ", beyond the range of the file's 32-bit floats.");
          converted[i] = static_cast<float>(values[i]);
        }
      return converted;
    }

    void
    write_array(std::ostream      &out,
                const char        *type,
                const std::string &name,
                const unsigned int n_components,
                const std::string &encoded)
    {
      out << "<DataArray type=\"" << type << "\"";
      if (!name.empty())
        out << " Name=\"" << name << "\"";
      if (n_components > 1)
        out << " NumberOfComponents=\"" << n_components << "\"";
      out << " format=\"binary\">\n" << encoded << "\n</DataArray>\n";
    }

    void
    write_fields(std::ostream                      &out,
                 const char                        *section,
                 const std::vector<VtuFile::Field> &fields,
                 const unsigned int                 n_entities)
    {
      out << "<" << section << ">\n";
      for (const auto &field : fields)
        {
          if (field.values == nullptr ||
              field.values->size() !=
                std::size_t(n_entities) * field.n_components)
            throw std::invalid_argument("VtuFile: the field <" + field.name +
                                        "> has the wrong number of values.");
          const std::vector<float> values =
            as_float(*field.values, "the field <" + field.name + ">");
          write_array(out,
                      "Float32",
                      field.name,
                      field.n_components,
                      VtuFile::encode(values.data(),
                                      values.size() * sizeof(float)));
        }
      out << "</" << section << ">\n";
    }
  } // namespace



  std::string
  VtuFile::encode(const void *data, const std::size_t n_bytes)
  {
    if (n_bytes > 0xffffffffu)
      throw std::length_error("VtuFile: a data array exceeds 4 GB.");
    // Blocks of compression_block_size bytes (the last one shorter; one
    // empty block for no data), compressed each on its own, on the threads:
    // the bytes depend on the block size alone.
    const auto        *bytes = static_cast<const Bytef *>(data);
    const std::size_t  block = compression_block_size;
    const unsigned int n =
      std::max<std::size_t>(1, (n_bytes + block - 1) / block);
    std::vector<std::vector<unsigned char>> compressed(n);
    std::vector<std::uint32_t>              header = {
                   n,
                   std::uint32_t(std::min(n_bytes, block)),
                   std::uint32_t(n_bytes - (n - 1) * block)};
    header.resize(3 + n);
    std::atomic<bool> failed = false;
    for_each_block(n, [&](const unsigned int k) {
      const std::size_t begin = k * block;
      const std::size_t count = std::min(n_bytes - begin, block);
      uLongf            size  = compressBound(count);
      compressed[k].resize(size);
      if (compress2(
            compressed[k].data(), &size, bytes + begin, count, Z_BEST_SPEED) !=
          Z_OK)
        failed = true;
      compressed[k].resize(size);
      header[3 + k] = std::uint32_t(size);
    });
    if (failed)
      throw std::runtime_error("VtuFile: zlib compression failed.");
    // VTK's header of compressed data (the number of blocks, the size of a
    // block, the size of the last block and the compressed size of each) is
    // encoded separately from the data, the blocks one after the other.
    std::vector<unsigned char> joined;
    for (const std::vector<unsigned char> &part : compressed)
      joined.insert(joined.end(), part.begin(), part.end());
    std::string encoded;
    append_base64(reinterpret_cast<const unsigned char *>(header.data()),
                  header.size() * sizeof(std::uint32_t),
                  encoded);
    append_base64(joined.data(), joined.size(), encoded);
    return encoded;
  }



  VtuFile::VtuFile(const std::vector<double>       &points,
                   const std::vector<unsigned int> &tetrahedra,
                   const unsigned int               points_per_cell)
    : n_points(points.size() / 3)
    , n_cells(tetrahedra.size() / points_per_cell)
  {
    if (points_per_cell != 3 && points_per_cell != 4)
      throw std::invalid_argument(
        "VtuFile: cells are triangles (3 points) or tetrahedra (4).");
    if (points.size() % 3 != 0 || tetrahedra.size() % points_per_cell != 0)
      throw std::invalid_argument("VtuFile: points need 3 coordinates, cells " +
                                  std::to_string(points_per_cell) +
                                  " points each.");
    for (const unsigned int p : tetrahedra)
      if (p >= n_points)
        throw std::invalid_argument(
          "VtuFile: a cell refers to a point that does not exist.");
    const std::vector<float> xyz = as_float(points, "a point coordinate");
    encoded_points = encode(xyz.data(), xyz.size() * sizeof(float));
    const std::vector<std::int32_t> connectivity(tetrahedra.begin(),
                                                 tetrahedra.end());
    encoded_connectivity =
      encode(connectivity.data(), connectivity.size() * sizeof(std::int32_t));
    std::vector<std::int32_t> offsets(n_cells);
    for (unsigned int e = 0; e < n_cells; ++e)
      offsets[e] = points_per_cell * (e + 1);
    encoded_offsets =
      encode(offsets.data(), offsets.size() * sizeof(std::int32_t));
    // VTK_TRIANGLE or VTK_TETRA
    const std::vector<std::uint8_t> types(n_cells,
                                          points_per_cell == 3 ? 5 : 10);
    encoded_types = encode(types.data(), types.size());
  }



  void
  VtuFile::write_parallel(std::ostream                   &out,
                          const std::vector<std::string> &pieces,
                          const std::vector<Field>       &point_fields,
                          const std::vector<Field>       &cell_fields)
  {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\""
        << (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__ ? "BigEndian" :
                                                     "LittleEndian")
        << "\" header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n"
        << "<PUnstructuredGrid GhostLevel=\"0\">\n"
        << "<PPoints>\n<PDataArray type=\"Float32\" "
           "NumberOfComponents=\"3\"/>\n</PPoints>\n";
    for (const auto &[section, fields] :
         {std::pair{"PPointData", &point_fields},
          std::pair{"PCellData", &cell_fields}})
      {
        out << "<" << section << ">\n";
        for (const Field &field : *fields)
          {
            out << "<PDataArray type=\"Float32\" Name=\"" << field.name << "\"";
            if (field.n_components > 1)
              out << " NumberOfComponents=\"" << field.n_components << "\"";
            out << "/>\n";
          }
        out << "</" << section << ">\n";
      }
    for (const std::string &piece : pieces)
      out << "<Piece Source=\"" << piece << "\"/>\n";
    out << "</PUnstructuredGrid>\n</VTKFile>\n";
  }



  void
  VtuFile::write_series(
    std::ostream                                      &out,
    const std::vector<std::pair<double, std::string>> &snapshots)
  {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
        << std::setprecision(17);
    for (const auto &[time, file] : snapshots)
      out << "<DataSet timestep=\"" << time
          << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
    out << "</Collection>\n</VTKFile>\n";
  }



  void
  VtuFile::write(std::ostream             &out,
                 const double              time,
                 const unsigned int        cycle,
                 const std::vector<Field> &point_fields,
                 const std::vector<Field> &cell_fields) const
  {
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\""
        << (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__ ? "BigEndian" :
                                                     "LittleEndian")
        << "\" header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">\n"
        << "<UnstructuredGrid>\n"
        << "<FieldData>\n"
        << "<DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" "
           "format=\"ascii\">"
        << time << "</DataArray>\n"
        << "<DataArray type=\"Int32\" Name=\"CYCLE\" NumberOfTuples=\"1\" "
           "format=\"ascii\">"
        << cycle << "</DataArray>\n"
        << "</FieldData>\n"
        << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
        << n_cells << "\">\n"
        << "<Points>\n";
    write_array(out, "Float32", "", 3, encoded_points);
    out << "</Points>\n<Cells>\n";
    write_array(out, "Int32", "connectivity", 1, encoded_connectivity);
    write_array(out, "Int32", "offsets", 1, encoded_offsets);
    write_array(out, "UInt8", "types", 1, encoded_types);
    out << "</Cells>\n";
    write_fields(out, "PointData", point_fields, n_points);
    write_fields(out, "CellData", cell_fields, n_cells);
    out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  }
} // namespace estep
