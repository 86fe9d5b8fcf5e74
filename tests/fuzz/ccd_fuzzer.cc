// Fuzz driver of the CCD query reader as `estep ccd` uses it: an input is a
// query file (CSV rows "xnum,xden,ynum,yden,znum,zden,truth", eight per query),
// read as vertex-face queries and as edge-edge queries (the reader takes the
// kind from a directory name in the path); every query read is classified
// (degenerate or not) and run through the conservative CCD of its kind, whose
// answer must be a time in [0, 1] within the iteration cap.
#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>

#include "fuzz_support.h"

#include <cstdlib>
#include <iostream>

extern "C" int
LLVMFuzzerInitialize(int *, char ***)
{
  estep_fuzz::initialize();
  return 0;
}



extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, const std::size_t size)
{
  using namespace estep::contact;
  static const std::string files[] = {
    estep_fuzz::scratch_file("vertex-face/queries.csv"),
    estep_fuzz::scratch_file("edge-edge/queries.csv")};
  const CcdSettings settings;
  for (const std::string &file : files)
    {
      estep_fuzz::write_file(file, data, size);
      std::vector<CcdQuery> queries;
      try
        {
          queries = read_ccd_query_file(file);
        }
      catch (const std::exception &error)
        {
          estep_fuzz::check_rejection(error);
          continue;
        }
      for (const CcdQuery &query : queries)
        {
          ccd_query_is_non_degenerate(query.start, query.end);
          const CcdResult result =
            query.edge_edge ? edge_edge_ccd(query.start, query.end, settings) :
                              vertex_face_ccd(query.start, query.end, settings);
          if (!(result.time >= 0. && result.time <= 1.) ||
              result.n_iterations > settings.max_iterations ||
              (result.capped && !result.hit))
            {
              std::cerr << "fuzz driver: CCD answer out of its range: hit "
                        << result.hit << ", time " << result.time
                        << ", iterations " << result.n_iterations << ", capped "
                        << result.capped << '\n';
              std::abort();
            }
        }
    }
  return 0;
}
