// The VTU file writer: a mesh and its fields become one piece of Float32
// arrays; a finite value beyond the range of Float32 (a blown-up run) is
// refused with a message naming it, instead of an undefined conversion.

#include <estep/io/vtu_file.h>

#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
  const std::vector<double> corners = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<unsigned int> tetrahedron = {0, 1, 2, 3};

  std::string
  error_of(const std::vector<double> &points,
           const std::vector<double> &point_values)
  {
    try
      {
        const estep::VtuFile file(points, tetrahedron);
        std::ostringstream   out;
        file.write(out, 0., 0, {{"speed", 1, &point_values}}, {});
      }
    catch (const std::range_error &e)
      {
        return e.what();
      }
    return "";
  }
} // namespace

TEST(VtuFile, WritesOnePieceOfFloat32Arrays)
{
  const std::vector<double> speed = {1., 2., 3., 4.};
  const estep::VtuFile      file(corners, tetrahedron);
  std::ostringstream        out;
  file.write(out, 0.5, 3, {{"speed", 1, &speed}}, {});
  const std::string text = out.str();
  EXPECT_NE(text.find("NumberOfPoints=\"4\" NumberOfCells=\"1\""),
            std::string::npos);
  EXPECT_NE(text.find("<DataArray type=\"Float32\" Name=\"speed\""),
            std::string::npos);
}

TEST(VtuFile, RefusesValuesBeyondFloat32)
{
  const std::vector<double> speed = {1., 2., 3., 4.};
  EXPECT_EQ(error_of(corners, speed), "");

  std::vector<double> far = corners;
  far[4]                  = 1e39;
  EXPECT_NE(error_of(far, speed).find("a point coordinate has the value"),
            std::string::npos);

  std::vector<double> fast = speed;
  fast[2]                  = -1e300;
  EXPECT_NE(error_of(corners, fast).find("the field <speed>"),
            std::string::npos);

  // Infinities and the largest float itself convert exactly.
  fast[2] = std::numeric_limits<double>::infinity();
  fast[1] = std::numeric_limits<float>::max();
  EXPECT_EQ(error_of(corners, fast), "");
}
