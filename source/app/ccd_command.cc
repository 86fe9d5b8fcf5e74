#include <estep/app/ccd_command.h>
#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace estep
{
  int
  run_ccd_command(const std::vector<std::string> &csv_files, std::ostream &out)
  {
    using namespace contact;
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
              if (entry.is_regular_file() && entry.path().extension() == ".csv")
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

    // Counts over all queries ([0]) and over the non-degenerate ones ([1],
    // ccd_query_is_non_degenerate()).
    struct Counts
    {
      std::size_t queries = 0, positive = 0, false_negative = 0,
                  false_positive = 0, capped = 0;
      double seconds = 0.;
    };
    const CcdSettings settings;
    Counts            counts[2];
    std::size_t       n_inexact = 0, n_edge_edge = 0;
    for (const std::string &file : files)
      {
        const std::vector<CcdQuery> queries = read_ccd_query_file(file);
        // The queries of each class are timed as one batch (a clock read
        // per query would cost a noticeable fraction of a microsecond).
        std::vector<std::size_t> by_class[2];
        for (std::size_t i = 0; i < queries.size(); ++i)
          by_class[ccd_query_is_non_degenerate(queries[i].start,
                                               queries[i].end)]
            .push_back(i);
        std::vector<CcdResult> results(queries.size());
        double                 seconds[2];
        for (unsigned int c = 0; c < 2; ++c)
          {
            const auto start = std::chrono::steady_clock::now();
            for (const std::size_t i : by_class[c])
              {
                const CcdQuery &q = queries[i];
                results[i]        = q.edge_edge ?
                                      edge_edge_ccd(q.start, q.end, settings) :
                                      vertex_face_ccd(q.start, q.end, settings);
              }
            seconds[c] = std::chrono::duration<double>(
                           std::chrono::steady_clock::now() - start)
                           .count();
          }
        for (std::size_t i = 0; i < queries.size(); ++i)
          {
            const CcdQuery &q = queries[i];
            n_inexact += !q.exact;
            n_edge_edge += q.edge_edge;
          }
        const auto add = [&](Counts &counts, const unsigned int c) {
          counts.seconds += seconds[c];
          for (const std::size_t i : by_class[c])
            {
              const bool truth = queries[i].truth, hit = results[i].hit;
              ++counts.queries;
              counts.positive += truth;
              counts.false_negative += (truth && !hit);
              counts.false_positive += (!truth && hit);
              counts.capped += results[i].capped;
            }
        };
        add(counts[0], 0);
        add(counts[0], 1);
        add(counts[1], 1);
      }
    const auto mean_us = [](const Counts &c) {
      return c.queries > 0 ? 1e6 * c.seconds / c.queries : 0.;
    };
    const Counts &all = counts[0], &generic = counts[1];
    out << "CCD files:           " << files.size() << "\n"
        << "queries:             " << all.queries << " (vertex-face "
        << all.queries - n_edge_edge << ", edge-edge " << n_edge_edge << ")\n"
        << "non-degenerate:      " << generic.queries
        << " (|det[x1 - x0, x2 - x0, x3 - x0]| > 2^-42 L^3 at t = 0 and 1, L "
           "the longest distance between the points)\n"
        << "positives:           " << all.positive << " (non-degenerate "
        << generic.positive << ")\n"
        << "false negatives:     " << all.false_negative << " (non-degenerate "
        << generic.false_negative << ")\n"
        << "false positives:     " << all.false_positive << " (non-degenerate "
        << generic.false_positive << ")\n"
        << "iteration cap hit:   " << all.capped << " (non-degenerate "
        << generic.capped << ")\n"
        << "mean time per query: " << mean_us(all)
        << " microseconds (non-degenerate " << mean_us(generic) << ")\n"
        << "(tolerance " << settings.tolerance << ", iteration cap "
        << settings.max_iterations << ")" << std::endl;
    if (n_inexact > 0)
      out
        << "warning: " << n_inexact
        << " queries have coordinates that are not exactly representable as doubles; "
           "their ground truth refers to the exact rationals"
        << std::endl;
    return all.false_negative == 0 ? 0 : 1;
  }
} // namespace estep
