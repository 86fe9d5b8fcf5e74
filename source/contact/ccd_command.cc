#include <estep/contact/ccd_command.h>
#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace estep
{
  namespace contact
  {
    int
    run_ccd_command(const std::vector<std::string> &csv_files,
                    std::ostream                   &out)
    {
      namespace fs = std::filesystem;
      if (csv_files.empty())
        throw std::runtime_error("estep ccd: no query file or directory given");
      std::vector<std::string> files;
      for (const std::string &name : csv_files)
        {
          std::error_code ec;
          if (fs::is_directory(name, ec))
            {
              std::vector<std::string> found;
              for (const auto &entry : fs::recursive_directory_iterator(name))
                if (entry.is_regular_file() &&
                    entry.path().extension() == ".csv")
                  found.push_back(entry.path().string());
              std::sort(found.begin(), found.end());
              files.insert(files.end(), found.begin(), found.end());
            }
          else if (fs::is_regular_file(name, ec))
            files.push_back(name);
          else
            throw std::runtime_error("estep ccd: " + name +
                                     " is neither a file nor a directory");
        }

      const CcdSettings settings;
      std::size_t       n_queries = 0, n_positive = 0, n_false_negative = 0,
                  n_false_positive = 0, n_capped = 0, n_inexact = 0,
                  n_edge_edge = 0;
      double seconds          = 0.;
      for (const std::string &file : files)
        {
          const std::vector<CcdQuery> queries = read_ccd_query_file(file);
          std::vector<char>           hits(queries.size());
          std::vector<char>           capped(queries.size());
          const auto                  start = std::chrono::steady_clock::now();
          for (std::size_t i = 0; i < queries.size(); ++i)
            {
              const CcdQuery &q = queries[i];
              const CcdResult r = q.edge_edge ?
                                    edge_edge_ccd(q.start, q.end, settings) :
                                    vertex_face_ccd(q.start, q.end, settings);
              hits[i]           = r.hit;
              capped[i]         = r.capped;
            }
          seconds += std::chrono::duration<double>(
                       std::chrono::steady_clock::now() - start)
                       .count();
          for (std::size_t i = 0; i < queries.size(); ++i)
            {
              ++n_queries;
              n_positive += queries[i].truth;
              n_false_negative += (queries[i].truth && !hits[i]);
              n_false_positive += (!queries[i].truth && hits[i]);
              n_capped += capped[i];
              n_inexact += !queries[i].exact;
              n_edge_edge += queries[i].edge_edge;
            }
        }
      out << "CCD files:           " << files.size() << "\n"
          << "queries:             " << n_queries << " (vertex-face "
          << n_queries - n_edge_edge << ", edge-edge " << n_edge_edge << ")\n"
          << "positives:           " << n_positive << "\n"
          << "false negatives:     " << n_false_negative << "\n"
          << "false positives:     " << n_false_positive << "\n"
          << "iteration cap hit:   " << n_capped << "\n"
          << "mean time per query: "
          << (n_queries > 0 ? 1e6 * seconds / n_queries : 0.)
          << " microseconds\n"
          << "(tolerance " << settings.tolerance << ", iteration cap "
          << settings.max_iterations << ")" << std::endl;
      if (n_inexact > 0)
        out
          << "warning: " << n_inexact
          << " queries have coordinates that are not exactly representable as doubles; "
             "their ground truth refers to the exact rationals"
          << std::endl;
      return n_false_negative == 0 ? 0 : 1;
    }
  } // namespace contact
} // namespace estep
