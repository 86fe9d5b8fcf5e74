// The VTU file writer: a mesh and its fields become one piece of Float32
// arrays; a finite value beyond the range of Float32 (a blown-up run) is
// refused with a message naming it, instead of an undefined conversion; an
// array is compressed in blocks with VTK's header, which decode to its bytes,
// the same on any number of threads.

#include <estep/base/parallel_blocks.h>
#include <estep/io/vtu_file.h>

#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdint>
#include <cstring>
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

  /** The bytes of the base64 text @p text (RFC 4648, padded). */
  std::vector<unsigned char>
  base64_bytes(const std::string &text)
  {
    const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<unsigned char> bytes;
    std::uint32_t              group = 0;
    unsigned int               bits  = 0;
    for (const char c : text)
      {
        if (c == '=')
          break;
        group = (group << 6) | alphabet.find(c);
        bits += 6;
        if (bits >= 8)
          {
            bits -= 8;
            bytes.push_back((group >> bits) & 0xff);
          }
      }
    return bytes;
  }

  /** The bytes VtuFile::encode() compressed into @p encoded, decoded as VTK's
   * reader does: the header (blocks, block size, size of the last block,
   * compressed sizes), then each block uncompressed in turn. Fails the test
   * on a header that does not fit the data. */
  std::vector<unsigned char>
  decoded(const std::string &encoded)
  {
    std::uint32_t first;
    std::memcpy(&first, base64_bytes(encoded.substr(0, 8)).data(), 4);
    const std::size_t header_bytes = 4 * (3 + std::size_t(first));
    const std::size_t header_chars = 4 * ((header_bytes + 2) / 3);
    const std::vector<unsigned char> header_text =
      base64_bytes(encoded.substr(0, header_chars));
    std::vector<std::uint32_t> header(3 + first);
    std::memcpy(header.data(), header_text.data(), header_bytes);
    const std::vector<unsigned char> data =
      base64_bytes(encoded.substr(header_chars));
    std::vector<unsigned char> bytes;
    std::size_t                at = 0;
    for (std::uint32_t k = 0; k < first; ++k)
      {
        uLongf size = (k + 1 < first) ? header[1] : header[2];
        std::vector<unsigned char> block(size);
        EXPECT_EQ(
          uncompress(block.data(), &size, data.data() + at, header[3 + k]),
          Z_OK);
        EXPECT_EQ(size, (k + 1 < first) ? header[1] : header[2]);
        bytes.insert(bytes.end(), block.begin(), block.begin() + size);
        at += header[3 + k];
      }
    EXPECT_EQ(at, data.size());
    return bytes;
  }
} // namespace

TEST(VtuFile, CompressesInBlocksThatDecodeToTheArray)
{
  const std::size_t block = estep::VtuFile::compression_block_size;
  for (const std::size_t n :
       {std::size_t(0), std::size_t(1000), block, 3 * block, 3 * block + 17})
    {
      std::vector<unsigned char> bytes(n);
      for (std::size_t i = 0; i < n; ++i)
        bytes[i] = static_cast<unsigned char>((i * 2654435761u) >> 13);
      estep::set_thread_count(1);
      const std::string one = estep::VtuFile::encode(bytes.data(), n);
      estep::set_thread_count(3);
      const std::string three = estep::VtuFile::encode(bytes.data(), n);
      EXPECT_EQ(one, three) << n << " bytes";
      EXPECT_EQ(decoded(one), bytes) << n << " bytes";
      std::uint32_t blocks;
      std::memcpy(&blocks, base64_bytes(one.substr(0, 8)).data(), 4);
      EXPECT_EQ(blocks, std::max<std::size_t>(1, (n + block - 1) / block));
    }
}

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
