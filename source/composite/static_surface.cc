#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <estep/composite/static_surface.h>
#include <estep/fem/gmsh_check.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace estep
{
  unsigned int
  StaticSurface::n_points() const
  {
    return points.size() / 3;
  }



  void
  StaticSurface::check() const
  {
    const std::string what = "surface <" + name + ">: ";
    if (points.size() % 3 != 0)
      throw std::runtime_error(what + "the number of coordinates is not a "
                                      "multiple of three.");
    if (triangles.empty())
      throw std::runtime_error(what + "no triangle.");
    for (const double x : points)
      if (!std::isfinite(x))
        throw std::runtime_error(what + "a coordinate is not finite.");
    for (const auto &t : triangles)
      {
        for (const unsigned int i : t)
          if (i >= n_points())
            throw std::runtime_error(what +
                                     "a triangle refers to a missing point.");
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
          throw std::runtime_error(what + "a triangle repeats a point.");
      }
  }



  namespace
  {
    /** Points with identical coordinates (exactly) become one, numbered in
     * the order of their first appearance. */
    class PointNumbering
    {
    public:
      explicit PointNumbering(StaticSurface &surface)
        : surface(surface)
      {}

      unsigned int
      operator()(const std::array<double, 3> &x)
      {
        const auto [it, inserted] =
          point_of.emplace(x, static_cast<unsigned int>(point_of.size()));
        if (inserted)
          surface.points.insert(surface.points.end(), x.begin(), x.end());
        return it->second;
      }

    private:
      StaticSurface                                &surface;
      std::map<std::array<double, 3>, unsigned int> point_of;
    };

    /** The little-endian unsigned 32-bit integer at @p bytes. */
    std::uint32_t
    little_endian_uint32(const unsigned char *bytes)
    {
      return bytes[0] | (bytes[1] << 8) | (bytes[2] << 16) |
             (static_cast<std::uint32_t>(bytes[3]) << 24);
    }

    /** The number of triangles of a binary STL file of @p size bytes whose
     * bytes 80 to 83 are @p count_bytes, if the size is that of so many
     * (84 + 50 per triangle); none otherwise. */
    std::optional<std::uint32_t>
    binary_stl_triangles(const unsigned char *count_bytes,
                         const std::uintmax_t size)
    {
      const std::uint32_t n = little_endian_uint32(count_bytes);
      if (size != 84 + 50 * static_cast<std::uintmax_t>(n))
        return std::nullopt;
      return n;
    }

    /** Whether the first 4 KiB of @p in hold a byte no text file has (a
     * control character other than white space): binary data (a binary
     * STL file's triangle count alone has such bytes). */
    bool
    holds_binary_bytes(std::istream &in)
    {
      char buffer[4096];
      in.read(buffer, sizeof(buffer));
      return std::any_of(buffer, buffer + in.gcount(), [](const char b) {
        const unsigned char c = b;
        return c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' &&
               c != '\v';
      });
    }

    /** The little-endian IEEE single at @p bytes. */
    double
    read_float(const unsigned char *bytes)
    {
      const std::uint32_t bits = little_endian_uint32(bytes);
      float               x;
      std::memcpy(&x, &bits, sizeof(x));
      return x;
    }

    void
    read_binary_stl(std::istream       &in,
                    const std::uint32_t n_triangles,
                    StaticSurface      &surface,
                    const std::string  &what)
    {
      PointNumbering point_number(surface);
      unsigned char  record[50];
      for (std::uint32_t t = 0; t < n_triangles; ++t)
        {
          if (!in.read(reinterpret_cast<char *>(record), sizeof(record)))
            throw std::runtime_error(what + "could not be read.");
          // 12 bytes of normal (not used), three vertices, 2 bytes of
          // attributes (not used).
          contact::TriangleIndices triangle;
          for (unsigned int v = 0; v < 3; ++v)
            {
              std::array<double, 3> x;
              for (unsigned int c = 0; c < 3; ++c)
                x[c] = read_float(record + 12 * (v + 1) + 4 * c);
              triangle[v] = point_number(x);
            }
          surface.triangles.push_back(triangle);
        }
    }
  } // namespace



  StaticSurface
  read_stl_surface(const std::string &filename)
  {
    const std::string what = "STL file <" + filename + ">: ";
    if (std::filesystem::is_directory(filename))
      throw std::runtime_error(what + "is a directory, not a file.");
    std::ifstream in(filename, std::ios::binary);
    if (!in)
      throw std::runtime_error(what + "cannot be opened.");

    StaticSurface surface;
    surface.name = filename;

    // Binary if the size is that of a binary file of the triangles its
    // bytes 80 to 83 count, whatever its header says (exporters often begin
    // it with "solid", as an ASCII file begins).
    {
      char                 header[84];
      std::error_code      error;
      const std::uintmax_t size = std::filesystem::file_size(filename, error);
      if (!error && in.read(header, sizeof(header)))
        {
          const auto *count =
            reinterpret_cast<const unsigned char *>(header) + 80;
          if (const auto n = binary_stl_triangles(count, size))
            {
              read_binary_stl(in, *n, surface, what);
              surface.check();
              return surface;
            }
          // Not a whole binary file, and not text either: one cut short.
          in.seekg(0);
          if (holds_binary_bytes(in))
            {
              const std::uintmax_t n = little_endian_uint32(count);
              std::ostringstream   message;
              message << what << "a binary STL file (it holds bytes no text "
                      << "file has) of " << size << " bytes, where the " << n
                      << " triangles its header counts take " << 84 + 50 * n
                      << " (the file is cut short or damaged).";
              throw std::runtime_error(message.str());
            }
        }
      in.clear();
      in.seekg(0);
    }

    PointNumbering            point_number(surface);
    std::vector<unsigned int> loop;
    // Where the reader is: each keyword is accepted in one place only, so
    // that a file cut short (or spliced) is refused, not read in part.
    enum class Place
    {
      before_solid,
      in_solid,
      in_facet,
      in_loop,
      after_loop,
      after_solid
    };
    Place       place = Place::before_solid;
    std::string word;
    const auto  expect = [&](const bool where_allowed) {
      if (!where_allowed)
        throw std::runtime_error(what + "unexpected <" + word +
                                 "> (the file is cut short or malformed).");
    };
    // Keywords in any case: some exporters write them in capitals.
    const auto read_keyword = [&]() -> bool {
      if (!(in >> word))
        return false;
      for (char &letter : word)
        letter =
          static_cast<char>(std::tolower(static_cast<unsigned char>(letter)));
      return true;
    };
    while (read_keyword())
      if (word == "solid")
        {
          expect(place == Place::before_solid || place == Place::after_solid);
          std::string rest;
          std::getline(in, rest); // the solid's name
          place = Place::in_solid;
        }
      else if (place == Place::before_solid)
        throw std::runtime_error(
          what + "neither an ASCII STL file (it does not start with 'solid') "
                 "nor a binary one (84 bytes and 50 per triangle).");
      else if (word == "facet")
        {
          expect(place == Place::in_solid);
          if (!read_keyword() || word != "normal")
            throw std::runtime_error(what + "'facet' without 'normal'.");
          std::string normal; // not used (exporters write NaN for some)
          std::getline(in, normal);
          place = Place::in_facet;
        }
      else if (word == "outer")
        {
          expect(place == Place::in_facet);
          if (!read_keyword() || word != "loop")
            throw std::runtime_error(what + "'outer' without 'loop'.");
          loop.clear();
          place = Place::in_loop;
        }
      else if (word == "vertex")
        {
          expect(place == Place::in_loop);
          std::array<double, 3> x;
          for (double &c : x)
            if (!(in >> c))
              throw std::runtime_error(what +
                                       "a vertex without three numbers.");
          loop.push_back(point_number(x));
        }
      else if (word == "endloop")
        {
          expect(place == Place::in_loop);
          if (loop.size() != 3)
            throw std::runtime_error(
              what + "a facet with " + std::to_string(loop.size()) +
              " vertices (only triangles are supported).");
          place = Place::after_loop;
        }
      else if (word == "endfacet")
        {
          expect(place == Place::after_loop);
          surface.triangles.push_back({{loop[0], loop[1], loop[2]}});
          place = Place::in_solid;
        }
      else if (word == "endsolid")
        {
          expect(place == Place::in_solid);
          std::string rest;
          std::getline(in, rest);
          place = Place::after_solid;
        }
      else
        throw std::runtime_error(what + "unexpected word <" + word + ">.");
    if (place == Place::before_solid)
      throw std::runtime_error(what + "empty.");
    if (place != Place::after_solid)
      throw std::runtime_error(what +
                               "ends before its 'endsolid' (the file is cut "
                               "short).");
    surface.check();
    return surface;
  }



  StaticSurface
  read_msh_surface(const std::string &filename)
  {
    const std::string what = "gmsh file <" + filename + ">: ";
    if (std::filesystem::is_directory(filename))
      throw std::runtime_error(what + "is a directory, not a file.");
    std::ifstream in(filename);
    if (!in)
      throw std::runtime_error(what + "cannot be opened.");
    dealii::Triangulation<2, 3> tria;
    try
      {
        check_gmsh_file(filename, 2);
        dealii::GridIn<2, 3> grid_in(tria);
        grid_in.read_msh(in);
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::ostringstream text;
        e.print_info(text);
        std::string message = text.str();
        message.erase(std::remove(message.begin(), message.end(), '\n'),
                      message.end());
        throw std::runtime_error(
          what + "not a gmsh surface mesh of triangles (" + message + ").");
      }
    catch (const std::exception &e)
      {
        throw std::runtime_error(
          what + "not a gmsh surface mesh of triangles (" + e.what() + ").");
      }
    if (tria.n_active_cells() == 0)
      throw std::runtime_error(what + "no triangle.");

    StaticSurface surface;
    surface.name = filename;
    std::vector<unsigned int> point_of_vertex(tria.n_vertices(), 0);
    const auto               &vertices = tria.get_vertices();
    const auto               &used     = tria.get_used_vertices();
    for (unsigned int i = 0; i < tria.n_vertices(); ++i)
      if (used[i])
        {
          point_of_vertex[i] = surface.n_points();
          for (unsigned int c = 0; c < 3; ++c)
            surface.points.push_back(vertices[i][c]);
        }
    for (const auto &cell : tria.active_cell_iterators())
      {
        if (cell->reference_cell() != dealii::ReferenceCells::Triangle)
          throw std::runtime_error(
            what + "has elements that are not triangles (only triangles are "
                   "supported).");
        surface.triangles.push_back({{point_of_vertex[cell->vertex_index(0)],
                                      point_of_vertex[cell->vertex_index(1)],
                                      point_of_vertex[cell->vertex_index(2)]}});
      }
    surface.check();
    return surface;
  }



  StaticSurface
  read_static_surface(const std::string &filename)
  {
    std::string extension;
    if (const auto dot = filename.rfind('.'); dot != std::string::npos)
      extension = filename.substr(dot + 1);
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](const unsigned char c) { return std::tolower(c); });
    if (extension == "stl")
      return read_stl_surface(filename);
    if (extension == "msh")
      return read_msh_surface(filename);
    throw std::runtime_error("surface file <" + filename +
                             ">: unknown extension (expected .stl or .msh).");
  }
} // namespace estep
