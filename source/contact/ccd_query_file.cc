#include <estep/contact/ccd_query_file.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace contact
  {
    namespace
    {
      [[noreturn]] void
      fail(const std::string &file,
           const unsigned int line,
           const std::string &what)
      {
        throw std::runtime_error(
          "CCD query file " + file +
          (line > 0 ? ", line " + std::to_string(line) : "") + ": " + what);
      }

      // A decimal integer as the nearest double; exact tells whether no
      // rounding happened.
      bool
      parse_integer(const std::string &s, double &value, bool &exact)
      {
        std::size_t i = 0;
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r'))
          ++i;
        std::size_t j = s.size();
        while (j > i &&
               (s[j - 1] == ' ' || s[j - 1] == '\t' || s[j - 1] == '\r'))
          --j;
        const std::string t = s.substr(i, j - i);
        std::size_t k = (!t.empty() && (t[0] == '-' || t[0] == '+')) ? 1 : 0;
        if (k == t.size())
          return false;
        for (std::size_t m = k; m < t.size(); ++m)
          if (t[m] < '0' || t[m] > '9')
            return false;
        value = std::strtod(t.c_str(), nullptr);
        // Exact iff printing the double back gives the same digits (ignoring
        // sign, zeros).
        std::size_t first = k;
        while (first + 1 < t.size() && t[first] == '0')
          ++first;
        char buffer[400];
        std::snprintf(buffer, sizeof(buffer), "%.0f", std::abs(value));
        exact = std::isfinite(value) && t.substr(first) == buffer;
        return true;
      }
    } // namespace



    std::vector<CcdQuery>
    read_ccd_query_file(const std::string &file_name)
    {
      bool edge_edge;
      if (file_name.find("edge-edge") != std::string::npos)
        edge_edge = true;
      else if (file_name.find("vertex-face") != std::string::npos)
        edge_edge = false;
      else
        fail(
          file_name,
          0,
          "the path names no query kind (a directory 'vertex-face' or 'edge-edge')");

      std::ifstream in(file_name);
      if (!in)
        fail(file_name, 0, "cannot open the file");

      std::vector<CcdQuery> queries;
      CcdQuery              query;
      query.edge_edge      = edge_edge;
      unsigned int row     = 0;
      unsigned int line_no = 0;
      std::string  line;
      while (std::getline(in, line))
        {
          ++line_no;
          if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue; // blank line
          std::vector<std::string> fields;
          std::stringstream        ss(line);
          std::string              field;
          while (std::getline(ss, field, ','))
            fields.push_back(field);
          if (fields.size() != 7)
            fail(
              file_name,
              line_no,
              "expected 7 comma-separated fields (xnum,xden,ynum,yden,znum,zden,truth), "
              "found " +
                std::to_string(fields.size()));
          Point3 p;
          for (unsigned int c = 0; c < 3; ++c)
            {
              double num, den;
              bool   exact_num, exact_den;
              if (!parse_integer(fields[2 * c], num, exact_num) ||
                  !parse_integer(fields[2 * c + 1], den, exact_den))
                fail(file_name,
                     line_no,
                     "coordinate " + std::to_string(c) +
                       " is not a pair of integers");
              if (den == 0.)
                fail(file_name, line_no, "zero denominator");
              if (!std::isfinite(num) || !std::isfinite(den))
                fail(file_name,
                     line_no,
                     "coordinate out of the range of double");
              int          exponent;
              const double mantissa = std::frexp(std::abs(den), &exponent);
              p[c]                  = num / den;
              query.exact =
                query.exact && exact_num && exact_den && mantissa == 0.5;
            }
          bool   exact_truth;
          double truth;
          if (!parse_integer(fields[6], truth, exact_truth) ||
              (truth != 0. && truth != 1.))
            fail(file_name, line_no, "the truth field must be 0 or 1");
          if (row == 0)
            query.truth = (truth == 1.);
          else if (query.truth != (truth == 1.))
            fail(file_name,
                 line_no,
                 "the truth value differs within one query");
          (row < 4 ? query.start[row] : query.end[row - 4]) = p;
          if (++row == 8)
            {
              queries.push_back(query);
              query           = CcdQuery();
              query.edge_edge = edge_edge;
              row             = 0;
            }
        }
      if (row != 0)
        fail(file_name,
             line_no,
             "the number of rows is not a multiple of 8 (last query has " +
               std::to_string(row) + " rows)");
      return queries;
    }
  } // namespace contact
} // namespace estep
