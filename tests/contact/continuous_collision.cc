// Conservative CCD: every query of the sample data set (no false negatives),
// contact times never later than the exact time on constructed cases, the
// command and its error messages.

#include <estep/contact/ccd_command.h>
#include <estep/contact/ccd_query_file.h>
#include <estep/contact/continuous_collision.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using namespace estep::contact;

namespace
{
  const std::string query_dir = ESTEP_CCD_QUERY_DIR;
} // namespace

TEST(ContinuousCollision, SampleQueriesHaveNoFalseNegatives)
{
  namespace fs = std::filesystem;
  if (!fs::is_directory(query_dir))
    GTEST_SKIP() << "sample queries not found at " << query_dir;
  std::size_t n = 0, n_pos = 0, n_fn = 0, n_fp = 0, n_capped = 0;
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
  std::cout << "sample queries: " << n << ", positives: " << n_pos
            << ", false negatives: " << n_fn << ", false positives: " << n_fp
            << ", capped: " << n_capped << std::endl;
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

TEST(ContinuousCollision, CommandCountsAndErrors)
{
  namespace fs = std::filesystem;
  if (fs::is_directory(query_dir))
    {
      std::ostringstream out;
      EXPECT_EQ(run_ccd_command({query_dir + "/unit-tests"}, out), 0);
      EXPECT_NE(out.str().find("false negatives:     0"), std::string::npos)
        << out.str();
    }
  const fs::path dir =
    fs::temp_directory_path() / "estep_ccd_test" / "vertex-face";
  fs::create_directories(dir);
  const std::string bad = (dir / "bad.csv").string();
  {
    std::ofstream f(bad);
    for (unsigned int i = 0; i < 8; ++i)
      f << (i == 5 ? "1,1,2,x,3,1,0" : "1,1,2,1,3,1,0") << "\n";
  }
  std::ostringstream out;
  try
    {
      run_ccd_command({dir.parent_path().string()}, out);
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
  EXPECT_THROW(run_ccd_command({"/nonexistent/estep"}, out),
               std::runtime_error);
  EXPECT_THROW(run_ccd_command({}, out), std::runtime_error);
  fs::remove_all(dir.parent_path());
}
