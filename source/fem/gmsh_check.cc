#include <estep/fem/gmsh_check.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace estep
{
  namespace
  {
    /**
     * The whitespace-separated tokens of a stream, as operator>> reads them,
     * each with its line, and the numbers read_msh() reads from them.
     */
    class Tokens
    {
    public:
      explicit Tokens(std::streambuf &buffer)
        : buffer(buffer)
      {}

      /** The next token; @p what says what read_msh() reads there. */
      const std::string &
      word(const std::string &what)
      {
        token.clear();
        int c = buffer.sbumpc();
        while (c != EOF && is_space(c))
          {
            line += (c == '\n');
            c = buffer.sbumpc();
          }
        if (c == EOF)
          fail("the file ends where " + what + " should follow");
        token_line = line;
        do
          {
            token.push_back(static_cast<char>(c));
            c = buffer.sbumpc();
        } while (c != EOF && !is_space(c));
        line += (c == '\n');
        return token;
      }

      /** The next token, which must be @p keyword. */
      void
      expect(const std::string &keyword)
      {
        if (word(keyword) != keyword)
          fail("expected " + keyword + ", found <" + shown() + ">");
      }

      /** Skip the tokens up to @p keyword, and it. */
      void
      skip_past(const std::string &keyword)
      {
        while (word(keyword) != keyword)
          {}
      }

      /**
       * An integer in [min, max] (@p what names it): a sign and digits, as
       * a whole token.
       */
      long long
      integer(const std::string &what, const long long min, const long long max)
      {
        word(what);
        const std::size_t first  = (token[0] == '+' || token[0] == '-') ? 1 : 0;
        bool              digits = first < token.size();
        for (std::size_t i = first; digits && i < token.size(); ++i)
          digits = (token[i] >= '0' && token[i] <= '9');
        if (!digits)
          fail(what + " must be an integer, found <" + shown() + ">");
        errno                 = 0;
        const long long value = std::strtoll(token.c_str(), nullptr, 10);
        if (errno == ERANGE || value < min || value > max)
          fail(what + " " + shown() + " is out of its range [" +
               std::to_string(min) + ", " + std::to_string(max) + "]");
        return value;
      }

      /** An int of read_msh(). */
      int
      signed_int(const std::string &what)
      {
        return static_cast<int>(integer(what, INT_MIN, INT_MAX));
      }

      /** An unsigned int of read_msh(). */
      unsigned int
      unsigned_int(const std::string &what)
      {
        return static_cast<unsigned int>(integer(what, 0, UINT_MAX));
      }

      /** A count read_msh() loops on (an unsigned long there; a larger count
       * than this could not be matched by the file). */
      long long
      count(const std::string &what)
      {
        return integer(what, 0, LLONG_MAX);
      }

      /** A finite double, written as operator>> reads it, as a whole token.
       */
      double
      real(const std::string &what)
      {
        word(what);
        std::size_t i      = (token[0] == '+' || token[0] == '-') ? 1 : 0;
        const auto  digits = [&] {
          const std::size_t start = i;
          while (i < token.size() && token[i] >= '0' && token[i] <= '9')
            ++i;
          return i - start;
        };
        std::size_t mantissa = digits();
        if (i < token.size() && token[i] == '.')
          {
            ++i;
            mantissa += digits();
          }
        bool valid = mantissa > 0;
        if (valid && i < token.size() && (token[i] == 'e' || token[i] == 'E'))
          {
            ++i;
            if (i < token.size() && (token[i] == '+' || token[i] == '-'))
              ++i;
            valid = digits() > 0;
          }
        if (!valid || i != token.size())
          fail(what + " must be a number, found <" + shown() + ">");
        errno              = 0;
        const double value = std::strtod(token.c_str(), nullptr);
        if (errno == ERANGE || !std::isfinite(value))
          fail(what + " " + shown() + " is out of the range of double");
        return value;
      }

      [[noreturn]] void
      fail(const std::string &message) const
      {
        throw std::runtime_error("line " + std::to_string(token_line) + ": " +
                                 message + ".");
      }

    private:
      static bool
      is_space(const int c)
      {
        return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' ||
               c == '\r';
      }

      /** The token, shortened for a message. */
      std::string
      shown() const
      {
        return token.size() <= 40 ? token : token.substr(0, 40) + "...";
      }

      std::streambuf &buffer;
      std::string     token;
      unsigned int    line = 1, token_line = 1;
    };



    /** The $Entities section (read_msh() keeps one physical tag of each). */
    void
    check_entities(Tokens &in, const unsigned int format)
    {
      const long long n_points   = in.count("the number of points"),
                      n_curves   = in.count("the number of curves"),
                      n_surfaces = in.count("the number of surfaces"),
                      n_volumes  = in.count("the number of volumes");
      const auto entity          = [&](const bool point) {
        in.signed_int("an entity tag");
        for (unsigned int i = 0; i < (point && format > 40 ? 3 : 6); ++i)
          in.real("a bounding box coordinate");
        const unsigned int n_physicals =
          in.unsigned_int("the number of physical tags");
        if (n_physicals > 1)
          in.fail("an entity with more than one physical tag");
        for (unsigned int i = 0; i < n_physicals; ++i)
          in.signed_int("a physical tag");
        if (!point)
          for (long long i = 0, n = in.count("the number of bounding entities");
               i < n;
               ++i)
            in.signed_int("a bounding entity");
      };
      for (long long i = 0; i < n_points; ++i)
        entity(true);
      for (const long long n : {n_curves, n_surfaces, n_volumes})
        for (long long i = 0; i < n; ++i)
          entity(false);
      in.expect("$EndEntities");
    }



    /** The $Nodes section after its keyword; the tags it defines, sorted. */
    std::vector<int>
    check_nodes(Tokens &in, const unsigned int format)
    {
      long long n_blocks = 1;
      if (format >= 40)
        n_blocks = in.signed_int("the number of node blocks");
      const long long n_nodes = in.unsigned_int("the number of nodes");
      if (format > 40)
        {
          in.signed_int("the smallest node tag");
          in.signed_int("the largest node tag");
        }
      std::vector<int> tags;
      long long        n_read = 0;
      for (long long block = 0; block < n_blocks; ++block)
        {
          long long n_block_nodes = n_nodes;
          int       parametric    = 0;
          if (format >= 40)
            {
              in.signed_int("an entity tag");
              in.signed_int("an entity dimension");
              parametric    = in.signed_int("the parametric flag");
              n_block_nodes = in.count("the number of nodes of a block");
            }
          if (format > 40)
            for (long long i = 0; i < n_block_nodes; ++i)
              tags.push_back(in.signed_int("a node tag"));
          for (long long i = 0; i < n_block_nodes; ++i)
            {
              if (format <= 40)
                tags.push_back(in.signed_int("a node tag"));
              for (unsigned int d = 0; d < (parametric != 0 ? 5 : 3); ++d)
                in.real("a node coordinate");
            }
          n_read += n_block_nodes;
          // read_msh() stores the nodes of every block into an array of the
          // announced size.
          if (n_read > n_nodes)
            in.fail("the node blocks hold more nodes than the " +
                    std::to_string(n_nodes) + " announced");
        }
      if (n_read != n_nodes)
        in.fail("the node blocks hold " + std::to_string(n_read) +
                " nodes, not the " + std::to_string(n_nodes) + " announced");
      in.expect(format == 10 ? "$ENDNOD" : "$EndNodes");
      std::sort(tags.begin(), tags.end());
      return tags;
    }



    /** The $Elements section after its keyword. */
    void
    check_elements(Tokens                 &in,
                   const unsigned int      format,
                   const unsigned int      dim,
                   const std::vector<int> &nodes)
    {
      long long n_blocks = 1;
      if (format >= 40)
        n_blocks = in.signed_int("the number of element blocks");
      const long long n_elements = in.unsigned_int("the number of elements");
      if (format > 40)
        {
          in.signed_int("the smallest element tag");
          in.signed_int("the largest element tag");
        }
      const auto node = [&] {
        const unsigned int tag = in.unsigned_int("a node of an element");
        if (tag > static_cast<unsigned int>(INT_MAX) ||
            !std::binary_search(nodes.begin(),
                                nodes.end(),
                                static_cast<int>(tag)))
          in.fail("an element names the node " + std::to_string(tag) +
                  ", which the file does not define");
      };
      for (long long block = 0; block < n_blocks; ++block)
        {
          long long n_block_elements = n_elements;
          int       type             = 0;
          if (format >= 40)
            {
              int entity_dimension;
              if (format == 40)
                {
                  in.signed_int("an entity tag");
                  entity_dimension = in.signed_int("an entity dimension");
                }
              else
                {
                  entity_dimension = in.signed_int("an entity dimension");
                  in.signed_int("an entity tag");
                }
              // read_msh() looks the entity up in an array of four.
              if (entity_dimension < 0 || entity_dimension > 3)
                in.fail("an entity dimension must be 0 to 3");
              type             = in.signed_int("an element type");
              n_block_elements = in.count("the number of elements of a block");
            }
          for (long long i = 0; i < n_block_elements; ++i)
            {
              long long n_nodes = -1; // as the type says
              if (format < 40)
                {
                  in.unsigned_int("an element number");
                  type = in.signed_int("an element type");
                }
              if (format < 20)
                {
                  in.unsigned_int("a physical region");
                  in.unsigned_int("an elementary region");
                  n_nodes = in.unsigned_int("the number of nodes");
                }
              else if (format < 40)
                {
                  const unsigned int n_tags =
                    in.unsigned_int("the number of tags");
                  for (unsigned int t = 0; t < n_tags; ++t)
                    in.unsigned_int("a tag");
                }
              else
                in.signed_int("an element tag");

              // The elements read_msh() reads for this dimension: cells,
              // boundary lines and faces, points.
              unsigned int n_read;
              bool         cell = false;
              if (type == 1)
                n_read = 2;
              else if (type == 2)
                {
                  n_read = 3;
                  cell   = (dim == 2);
                }
              else if (type == 3)
                {
                  n_read = 4;
                  cell   = (dim == 2);
                }
              else if ((type == 4 || type == 5) && dim == 3)
                {
                  n_read = (type == 4 ? 4 : 8);
                  cell   = true;
                }
              else if (type == 15)
                {
                  if (format < 20 && n_nodes != 1)
                    in.fail("a point element must have one node");
                  in.unsigned_int("the node of a point");
                  continue;
                }
              else
                in.fail("element type " + std::to_string(type) +
                        " is not one of the types deal.II reads for a mesh "
                        "of dimension " +
                        std::to_string(dim));
              if (cell && n_nodes >= 0 && n_nodes != n_read)
                in.fail("an element of type " + std::to_string(type) +
                        " must have " + std::to_string(n_read) + " nodes");
              for (unsigned int k = 0; k < n_read; ++k)
                node();
            }
        }
      in.expect(format == 10 ? "$ENDELM" : "$EndElements");
    }
  } // namespace



  void
  check_gmsh_file(const std::string &filename, const unsigned int dim)
  {
    std::ifstream file(filename, std::ios::binary);
    if (!file)
      throw std::runtime_error("cannot open the file.");
    Tokens             in(*file.rdbuf());
    const std::string &first = in.word("$MeshFormat or $NOD");
    unsigned int       format;
    if (first == "$NOD")
      format = 10;
    else if (first == "$MeshFormat")
      {
        const double version = in.real("the version");
        // As read_msh() derives the format from the version (once the
        // version is known to be in range: the conversion is undefined
        // otherwise).
        const bool in_range = (version >= 2. && version <= 4.1);
        format = in_range ? static_cast<unsigned int>(version * 10) : 0;
        if (!(format == 20 || format == 21 || format == 22 || format == 40 ||
              format == 41))
          in.fail("gmsh format " + std::to_string(version) +
                  " is not one deal.II reads (1, 2.0 to 2.2, 4.0, 4.1)");
        if (in.unsigned_int("the file type") != 0)
          in.fail("only ASCII gmsh files are read (file type 0)");
        if (in.unsigned_int("the size of a double") != sizeof(double))
          in.fail("the size of a double must be 8");
        in.expect("$EndMeshFormat");
        std::string section = in.word("$Nodes");
        if (section == "$PhysicalNames")
          {
            in.skip_past("$EndPhysicalNames");
            section = in.word("$Nodes");
          }
        if (section == "$Entities")
          {
            check_entities(in, format);
            section = in.word("$Nodes");
          }
        if (section == "$PartitionedEntities")
          {
            in.skip_past("$EndPartitionedEntities");
            section = in.word("$Nodes");
          }
        if (section != "$Nodes")
          in.fail("expected $Nodes, found <" + section + ">");
      }
    else
      in.fail("the file does not start with $MeshFormat or $NOD");

    const std::vector<int> nodes = check_nodes(in, format);
    in.expect(format == 10 ? "$ELM" : "$Elements");
    check_elements(in, format, dim, nodes);
  }
} // namespace estep
