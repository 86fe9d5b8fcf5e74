// Conservative CCD: every query of the sample data set (no false negatives),
// exact contacts constructed on a dyadic grid (many of them degenerate) always
// found, contact times never later than the exact time on constructed cases,
// the non-degeneracy criterion, the query file's error messages.

#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

using namespace estep::contact;

namespace
{
  const std::string query_dir = ESTEP_CCD_QUERY_DIR;

  /** Why a test fails when the sample queries are missing. */
  std::string
  missing_query_dir_message()
  {
    return "the CCD sample queries are missing: directory " + query_dir +
           " not found";
  }
} // namespace

TEST(ContinuousCollision, SampleQueriesHaveNoFalseNegatives)
{
  namespace fs = std::filesystem;
  ASSERT_TRUE(fs::is_directory(query_dir)) << missing_query_dir_message();
  std::size_t n = 0, n_pos = 0, n_fn = 0, n_fp = 0, n_capped = 0;
  std::size_t n_generic = 0, n_generic_pos = 0, n_generic_fp = 0;
  for (const auto &entry : fs::recursive_directory_iterator(query_dir))
    {
      if (entry.path().extension() != ".csv")
        continue;
      for (const CcdQuery &q : read_ccd_query_file(entry.path().string()))
        {
          ASSERT_TRUE(q.exact);
          const CcdResult r = q.edge_edge ? edge_edge_ccd(q.start, q.end) :
                                            vertex_face_ccd(q.start, q.end);
          ++n;
          n_pos += q.truth;
          n_capped += r.capped;
          if (q.truth && !r.hit)
            {
              ++n_fn;
              ADD_FAILURE()
                << "false negative in " << entry.path() << ", query " << n;
            }
          n_fp += (!q.truth && r.hit);
          if (ccd_query_is_non_degenerate(q.start, q.end))
            {
              ++n_generic;
              n_generic_pos += q.truth;
              n_generic_fp += (!q.truth && r.hit);
            }
          if (r.hit)
            {
              EXPECT_GE(r.time, 0.);
              EXPECT_LE(r.time, 1.);
            }
        }
    }
  EXPECT_EQ(n, 4884u);
  EXPECT_EQ(n_pos, 225u);
  EXPECT_EQ(n_fn, 0u);
  // The classification is a pure function of the data (a regression check of
  // ccd_query_is_non_degenerate() on real queries).
  EXPECT_EQ(n_generic, 4585u);
  EXPECT_EQ(n_generic_pos, 188u);
  std::cout << "sample queries: " << n << ", positives: " << n_pos
            << ", false negatives: " << n_fn << ", false positives: " << n_fp
            << ", capped: " << n_capped << "; non-degenerate: " << n_generic
            << ", positives: " << n_generic_pos
            << ", false positives: " << n_generic_fp << std::endl;
}

namespace
{
  // Queries with an exact contact at time tau: positions at tau and
  // velocities on a coarse dyadic grid, so that the positions at t = 0 and 1
  // and the contact point are exact doubles. The coarse grid makes coplanar,
  // parallel and touching-at-the-ends configurations frequent.
  struct ExactContact
  {
    std::array<Point3, 4> start, end;
    double                tau;
  };

  ExactContact
  exact_contact(std::mt19937_64 &rng, const bool edge_edge)
  {
    std::uniform_int_distribution<int> grid(-4, 4), weight(0, 4), time(0, 4);
    const auto                         random_point = [&]() {
      return Point3{{grid(rng) / 4., grid(rng) / 4., grid(rng) / 4.}};
    };
    ExactContact          c;
    std::array<Point3, 4> at_tau;
    if (edge_edge)
      {
        // X = a0 + s (a1 - a0) = b0 + r (b1 - b0) at tau.
        at_tau[0]      = random_point();
        at_tau[1]      = random_point();
        const double s = weight(rng) / 4.;
        Point3       x;
        for (unsigned int k = 0; k < 3; ++k)
          x[k] = at_tau[0][k] + s * (at_tau[1][k] - at_tau[0][k]);
        const Point3 w = random_point();
        const double r = weight(rng) / 4.;
        for (unsigned int k = 0; k < 3; ++k)
          {
            at_tau[2][k] = x[k] - r * w[k];
            at_tau[3][k] = x[k] + (1. - r) * w[k];
          }
      }
    else
      {
        // p = (i A + j B + k C) / 4 with i + j + k = 4 at tau.
        for (unsigned int a = 1; a < 4; ++a)
          at_tau[a] = random_point();
        const int i = weight(rng),
                  j = std::uniform_int_distribution<int>(0, 4 - i)(rng),
                  k = 4 - i - j;
        for (unsigned int d = 0; d < 3; ++d)
          at_tau[0][d] =
            (i * at_tau[1][d] + j * at_tau[2][d] + k * at_tau[3][d]) / 4.;
      }
    c.tau = time(rng) / 4.;
    for (unsigned int a = 0; a < 4; ++a)
      {
        // Half of the points keep still (static faces and edges are common).
        const Point3 v = (weight(rng) % 2) ? random_point() : Point3{};
        for (unsigned int d = 0; d < 3; ++d)
          {
            c.start[a][d] = at_tau[a][d] - c.tau * v[d];
            c.end[a][d]   = at_tau[a][d] + (1. - c.tau) * v[d];
          }
      }
    return c;
  }
} // namespace

TEST(ContinuousCollision, ExactContactsAreAlwaysFound)
{
  std::mt19937_64 rng(32);
  std::size_t     n_degenerate = 0;
  for (unsigned int i = 0; i < 20000; ++i)
    {
      const bool         edge_edge = (i % 2 == 1);
      const ExactContact c         = exact_contact(rng, edge_edge);
      const CcdResult    r         = edge_edge ? edge_edge_ccd(c.start, c.end) :
                                                 vertex_face_ccd(c.start, c.end);
      ASSERT_TRUE(r.hit) << "query " << i << " tau " << c.tau;
      EXPECT_LE(r.time, c.tau) << "query " << i;
      n_degenerate += !ccd_query_is_non_degenerate(c.start, c.end);
    }
  // Both classes occur (a contact at t = 0 or 1 alone makes a query
  // degenerate).
  EXPECT_GT(n_degenerate, 4000u);
  EXPECT_LT(n_degenerate, 19000u);
}

TEST(ContinuousCollision, NonDegeneracyCriterion)
{
  const std::array<Point3, 4> generic = {
    {{{0.1, 0.2, 1.}}, {{0., 0., 0.}}, {{1., 0., 0.}}, {{0., 1., 0.}}}};
  std::array<Point3, 4> moved = generic;
  moved[0][2]                 = -1.;
  EXPECT_TRUE(ccd_query_is_non_degenerate(generic, moved));
  // Invariant under scaling and translation.
  for (const double scale : {1e-6, 1e6})
    {
      std::array<Point3, 4> a = generic, b = moved;
      for (auto *x : {&a, &b})
        for (Point3 &p : *x)
          for (unsigned int k = 0; k < 3; ++k)
            p[k] = scale * p[k] + 1e3 * scale * (k + 1);
      EXPECT_TRUE(ccd_query_is_non_degenerate(a, b)) << scale;
    }
  // Contact at t = 0 or t = 1: the vertex lies in the face's plane.
  std::array<Point3, 4> touching = generic;
  touching[0][2]                 = 0.;
  EXPECT_FALSE(ccd_query_is_non_degenerate(touching, moved));
  EXPECT_FALSE(ccd_query_is_non_degenerate(generic, touching));
  // Parallel edges, exactly and up to rounding-sized noise (as in data
  // produced by rotating a configuration in floating point).
  const std::array<Point3, 4> parallel = {
    {{{0., 0.6, 0.}}, {{1., 0.6, 0.}}, {{0., 0.5, 1e-17}}, {{1., 0.5, 0.}}}};
  std::array<Point3, 4> exactly_parallel = parallel;
  exactly_parallel[2][2]                 = 0.;
  EXPECT_FALSE(ccd_query_is_non_degenerate(parallel, generic));
  EXPECT_FALSE(ccd_query_is_non_degenerate(generic, exactly_parallel));
  // Three collinear points (degenerate face), a collapsed edge.
  std::array<Point3, 4> collinear = generic;
  collinear[3]                    = {{2., 0., 0.}};
  EXPECT_FALSE(ccd_query_is_non_degenerate(collinear, moved));
  std::array<Point3, 4> collapsed = generic;
  collapsed[2]                    = collapsed[1];
  EXPECT_FALSE(ccd_query_is_non_degenerate(generic, collapsed));
  // The threshold: a unit triangle and a point at height 1e-11 above it
  // (relative volume 1e-11 / 2^(3/2)) count as non-degenerate, at height
  // 1e-14 not, wherever the point is.
  std::array<Point3, 4> thin = {
    {{{0.3, 0.3, 1e-11}}, {{0., 0., 0.}}, {{1., 0., 0.}}, {{0., 1., 0.}}}};
  EXPECT_TRUE(ccd_query_is_non_degenerate(thin, generic));
  thin[0][2] = 1e-14;
  EXPECT_FALSE(ccd_query_is_non_degenerate(thin, generic));
  // Near a vertex of the face (near contact): its polar sine seen from the
  // point would be large, the relative volume is not.
  thin[0] = {{0., 0., 1e-14}};
  EXPECT_FALSE(ccd_query_is_non_degenerate(thin, generic));
}

TEST(ContinuousCollision, TimeIsNeverLate)
{
  std::mt19937_64                        rng(31);
  std::uniform_real_distribution<double> u(0., 1.);
  for (unsigned int i = 0; i < 500; ++i)
    {
      // A point crossing the plane z = 0 at time tau inside a fixed triangle.
      const double tau = u(rng);
      const double a = u(rng), b = u(rng) * (1. - a);
      const Point3 A = {{0., 0., 0.}}, B = {{1., 0., 0.}}, C = {{0., 1., 0.}};
      const double z0 = 0.5 + u(rng), vz = -z0 / tau;
      const std::array<Point3, 4> start = {{{{a, b, z0}}, A, B, C}};
      const std::array<Point3, 4> end   = {{{{a, b, z0 + vz}}, A, B, C}};
      const CcdResult             r     = vertex_face_ccd(start, end);
      ASSERT_TRUE(r.hit);
      EXPECT_LE(r.time, tau);
      EXPECT_GE(r.time, tau - 1e-5 * std::abs(z0 / vz) - 1e-6);

      // Two crossing edges, one moving down onto the other, touching at tau.
      const std::array<Point3, 4> e0 = {
        {{{-1., 0.3, z0}}, {{1., 0.3, z0}}, {{0.2, -1., 0.}}, {{0.2, 1., 0.}}}};
      std::array<Point3, 4> e1 = e0;
      e1[0][2] = e1[1][2] = z0 + vz;
      const CcdResult s   = edge_edge_ccd(e0, e1);
      ASSERT_TRUE(s.hit);
      EXPECT_LE(s.time, tau);
      EXPECT_GE(s.time, tau - 1e-5 * std::abs(z0 / vz) - 1e-6);

      // Miss: the point passes beside the triangle.
      std::array<Point3, 4> m0 = start, m1 = end;
      m0[0][0] = m1[0][0] = 1.2;
      m0[0][1] = m1[0][1] = 0.5;
      EXPECT_FALSE(vertex_face_ccd(m0, m1).hit);
    }
}

TEST(ContinuousCollision, QueryFileErrorsNameTheFileAndLine)
{
  namespace fs = std::filesystem;
  const fs::path dir =
    fs::temp_directory_path() / "estep_ccd_query_test" / "vertex-face";
  fs::create_directories(dir);
  const std::string bad = (dir / "bad.csv").string();
  {
    std::ofstream f(bad);
    for (unsigned int i = 0; i < 8; ++i)
      f << (i == 5 ? "1,1,2,x,3,1,0" : "1,1,2,1,3,1,0") << "\n";
  }
  try
    {
      read_ccd_query_file(bad);
      ADD_FAILURE() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find(bad), std::string::npos) << what;
      EXPECT_NE(what.find("line 6"), std::string::npos) << what;
    }
  {
    std::ofstream f(bad);
    f << "1,1,2,1,3,1,0\n";
  }
  EXPECT_THROW(read_ccd_query_file(bad), std::runtime_error);
  fs::remove_all(dir.parent_path());
}
