// Performance of the contact area: triangle-triangle tests per second, broad
// phase of two touching spheres of 1e5 boundary triangles each (self query over
// both, without and with a group per sphere, and body versus body), CCD time
// per query (all sample queries and the
// non-degenerate ones).
//
// Run: benchmark_contact_benchmark [--benchmark_filter=...]. The CCD benchmarks
// read the sample queries of the CCD data set from ESTEP_CCD_QUERY_DIR
// (environment) or from the data directory kept beside the source tree (found
// through __FILE__), and are skipped if absent.

#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>
#include <estep/contact/penalty_contact.h>
#include <estep/contact/triangle_intersection.h>

#include <benchmark/benchmark.h>

#include "../tests/contact/test_meshes.h"

#include <cstdlib>
#include <filesystem>
#include <random>

using namespace estep::contact;

namespace
{
  std::vector<std::pair<Triangle3, Triangle3>>
  generic_pairs(const unsigned int n)
  {
    std::mt19937_64                              rng(1);
    std::uniform_real_distribution<double>       u(0., 1.);
    std::vector<std::pair<Triangle3, Triangle3>> pairs(n);
    for (auto &[a, b] : pairs)
      for (auto *T : {&a, &b})
        for (auto &p : *T)
          for (double &x : p)
            x = u(rng);
    return pairs;
  }

  void
  BM_TriangleTriangleTest(benchmark::State &state)
  {
    const auto  pairs = generic_pairs(4096);
    std::size_t i = 0, n_yes = 0;
    for (auto _ : state)
      {
        const auto &p = pairs[i++ & 4095];
        n_yes += triangles_intersect(p.first, p.second);
      }
    benchmark::DoNotOptimize(n_yes);
    state.SetItemsProcessed(state.iterations());
    state.counters["intersecting_fraction"] =
      double(n_yes) / state.iterations();
  }
  BENCHMARK(BM_TriangleTriangleTest);

  void
  BM_TriangleTriangleIntersection(benchmark::State &state)
  {
    const auto  pairs = generic_pairs(4096);
    std::size_t i     = 0;
    for (auto _ : state)
      {
        const auto &p = pairs[i++ & 4095];
        benchmark::DoNotOptimize(intersect_triangles(p.first, p.second));
      }
    state.SetItemsProcessed(state.iterations());
  }
  BENCHMARK(BM_TriangleTriangleIntersection);

  struct TwoSpheres
  {
    std::vector<double> q;
    // All triangles (both spheres), and each sphere's, all indexing q.
    std::vector<TriangleIndices> triangles, first, second;
    TwoSpheres()
    {
      // 2 * 224 * 223 = 99,904 triangles per sphere; the spheres touch (overlap
      // 1e-3 R).
      estep_test::add_sphere(q, first, 0., 0., 0., 1., 224, 224);
      estep_test::add_sphere(q, second, 1.999, 0.01, 0.02, 1., 224, 224);
      triangles = first;
      triangles.insert(triangles.end(), second.begin(), second.end());
    }
  };

  const TwoSpheres &
  two_spheres()
  {
    static const TwoSpheres s;
    return s;
  }

  // Self case: one hierarchy over both spheres, all non-adjacent pairs (most
  // of them between neighbours on the same sphere).
  // Argument 1: the same with a group per sphere (no self-contact), so that
  // the pairs within a sphere are pruned with their subtrees instead of found
  // and discarded.
  void
  BM_BroadPhaseSelfBuildAndQuery(benchmark::State &state)
  {
    const TwoSpheres         &s = two_spheres();
    std::vector<unsigned int> groups;
    if (state.range(0) == 1)
      {
        groups.assign(s.triangles.size(), 0u);
        std::fill(groups.begin() + s.first.size(), groups.end(), 1u);
      }
    BoundingVolumeHierarchy                            bvh(s.triangles, groups);
    std::vector<std::pair<unsigned int, unsigned int>> pairs;
    for (auto _ : state)
      {
        bvh.build(s.q.data(), s.q.size());
        bvh.find_pairs(pairs);
      }
    state.counters["triangles"]       = s.triangles.size();
    state.counters["candidate_pairs"] = pairs.size();
  }
  BENCHMARK(BM_BroadPhaseSelfBuildAndQuery)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

  void
  BM_BroadPhaseSelfRefitAndQuery(benchmark::State &state)
  {
    const TwoSpheres                                  &s = two_spheres();
    BoundingVolumeHierarchy                            bvh(s.triangles);
    std::vector<std::pair<unsigned int, unsigned int>> pairs;
    bvh.build(s.q.data(), s.q.size());
    for (auto _ : state)
      {
        bvh.refit(s.q.data(), s.q.size());
        bvh.find_pairs(pairs);
      }
    state.counters["candidate_pairs"] = pairs.size();
  }
  BENCHMARK(BM_BroadPhaseSelfRefitAndQuery)->Unit(benchmark::kMillisecond);

  // Body versus body: one hierarchy per sphere, the pairs between them (what
  // contact between two bodies needs).
  void
  BM_BroadPhaseBodiesBuildAndQuery(benchmark::State &state)
  {
    const TwoSpheres       &s = two_spheres();
    BoundingVolumeHierarchy first(s.first), second(s.second);
    std::vector<std::pair<unsigned int, unsigned int>> pairs;
    for (auto _ : state)
      {
        first.build(s.q.data(), s.q.size());
        second.build(s.q.data(), s.q.size());
        first.find_pairs(second, pairs);
      }
    state.counters["triangles"]       = s.triangles.size();
    state.counters["candidate_pairs"] = pairs.size();
  }
  BENCHMARK(BM_BroadPhaseBodiesBuildAndQuery)->Unit(benchmark::kMillisecond);

  void
  BM_BroadPhaseBodiesRefitAndQuery(benchmark::State &state)
  {
    const TwoSpheres       &s = two_spheres();
    BoundingVolumeHierarchy first(s.first), second(s.second);
    std::vector<std::pair<unsigned int, unsigned int>> pairs;
    first.build(s.q.data(), s.q.size());
    second.build(s.q.data(), s.q.size());
    for (auto _ : state)
      {
        first.refit(s.q.data(), s.q.size());
        second.refit(s.q.data(), s.q.size());
        first.find_pairs(second, pairs);
      }
    state.counters["candidate_pairs"] = pairs.size();
  }
  BENCHMARK(BM_BroadPhaseBodiesRefitAndQuery)->Unit(benchmark::kMillisecond);

  void
  BM_PenaltyEnergyTwoSpheres(benchmark::State &state)
  {
    const TwoSpheres &s = two_spheres();
    PenaltyContact    contact(s.triangles, 1e-3);
    double            e = 0.;
    for (auto _ : state)
      e = contact.energy(s.q.data(), s.q.size());
    state.counters["energy"] = e;
    state.counters["intersecting_pairs"] =
      contact.n_intersecting_pairs(s.q.data(), s.q.size());
  }
  BENCHMARK(BM_PenaltyEnergyTwoSpheres)->Unit(benchmark::kMillisecond);

  std::vector<CcdQuery>
  sample_queries(const char *subset)
  {
    namespace fs              = std::filesystem;
    const char           *env = std::getenv("ESTEP_CCD_QUERY_DIR");
    const fs::path        dir = env ? fs::path(env) :
                                      fs::path(__FILE__).parent_path().parent_path() /
                                 "../shared/data/ccd-sample-queries";
    std::vector<CcdQuery> queries;
    if (!fs::is_directory(dir))
      return queries;
    for (const auto &e : fs::recursive_directory_iterator(dir))
      if (e.path().extension() == ".csv" &&
          e.path().string().find(subset) != std::string::npos)
        for (const auto &q : read_ccd_query_file(e.path().string()))
          queries.push_back(q);
    return queries;
  }

  void
  run_ccd(benchmark::State &state, const std::vector<CcdQuery> &queries)
  {
    if (queries.empty())
      {
        state.SkipWithError(
          "no CCD sample queries found (set ESTEP_CCD_QUERY_DIR)");
        return;
      }
    std::size_t i = 0, hits = 0;
    for (auto _ : state)
      {
        const CcdQuery &q = queries[i++ % queries.size()];
        hits += (q.edge_edge ? edge_edge_ccd(q.start, q.end) :
                               vertex_face_ccd(q.start, q.end))
                  .hit;
      }
    benchmark::DoNotOptimize(hits);
    state.SetItemsProcessed(state.iterations());
    state.counters["queries"] = queries.size();
  }

  void
  BM_CcdSampleQueriesAll(benchmark::State &state)
  {
    static const auto queries = sample_queries("");
    run_ccd(state, queries);
  }
  BENCHMARK(BM_CcdSampleQueriesAll)->Unit(benchmark::kMicrosecond)->MinTime(2.);

  // The sample queries that ccd_query_is_non_degenerate() accepts.
  void
  BM_CcdSampleQueriesNonDegenerate(benchmark::State &state)
  {
    static const auto queries = [] {
      std::vector<CcdQuery> generic;
      for (const CcdQuery &q : sample_queries(""))
        if (ccd_query_is_non_degenerate(q.start, q.end))
          generic.push_back(q);
      return generic;
    }();
    run_ccd(state, queries);
  }
  BENCHMARK(BM_CcdSampleQueriesNonDegenerate)
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(2.);

  // The scenes with no deliberately degenerate motion (sliding and crack
  // scenes).
  void
  BM_CcdSampleQueriesSliding(benchmark::State &state)
  {
    static const auto queries = sample_queries("sliding");
    run_ccd(state, queries);
  }
  BENCHMARK(BM_CcdSampleQueriesSliding)->Unit(benchmark::kMicrosecond);

  // Generic random linear motions of unit-size primitives (non-degenerate).
  void
  BM_CcdRandomGeneric(benchmark::State &state)
  {
    std::mt19937_64                        rng(5);
    std::uniform_real_distribution<double> u(0., 1.);
    std::vector<CcdQuery>                  queries(4096);
    for (std::size_t i = 0; i < queries.size(); ++i)
      {
        CcdQuery &q = queries[i];
        q.edge_edge = (i % 2);
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int k = 0; k < 3; ++k)
            {
              q.start[a][k] = u(rng);
              q.end[a][k]   = q.start[a][k] + 0.3 * (u(rng) - 0.5);
            }
      }
    run_ccd(state, queries);
  }
  BENCHMARK(BM_CcdRandomGeneric)->Unit(benchmark::kMicrosecond);
} // namespace

BENCHMARK_MAIN();
