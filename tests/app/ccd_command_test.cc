// The command `estep ccd`: its counts on the sample queries (no false
// negatives), and its errors naming the file and line of a malformed query
// file, a missing path or an empty list.

#include <estep/app/ccd_command.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace
{
  const std::string query_dir = ESTEP_CCD_QUERY_DIR;
} // namespace

TEST(CcdCommand, CountsAndErrors)
{
  namespace fs = std::filesystem;
  EXPECT_TRUE(fs::is_directory(query_dir))
    << "the CCD sample queries are missing: directory " << query_dir
    << " not found";
  if (fs::is_directory(query_dir))
    {
      std::ostringstream out;
      EXPECT_EQ(estep::run_ccd_command({query_dir + "/unit-tests"}, out), 0);
      EXPECT_NE(out.str().find("false negatives:     0 (non-degenerate 0)"),
                std::string::npos)
        << out.str();
      EXPECT_NE(out.str().find("non-degenerate:      "), std::string::npos)
        << out.str();
    }
  const fs::path dir =
    fs::temp_directory_path() / "estep_ccd_command_test" / "vertex-face";
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
      estep::run_ccd_command({dir.parent_path().string()}, out);
      ADD_FAILURE() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find(bad), std::string::npos) << what;
      EXPECT_NE(what.find("line 6"), std::string::npos) << what;
    }
  EXPECT_THROW(estep::run_ccd_command({"/nonexistent/estep"}, out),
               std::runtime_error);
  EXPECT_THROW(estep::run_ccd_command({}, out), std::runtime_error);
  fs::remove_all(dir.parent_path());
}
