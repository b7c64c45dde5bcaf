// The NRRD reader on tiny volumes the test writes by hand (a text header, a blank line, the
// samples): sizes, spacings and values x fastest, every type spelling in both byte orders, space
// directions as spacings, detached data, byte and line skips, gzip samples, and bad headers or
// short data refused with InvalidInput naming load_nrrd, the file and the line at fault.

#include "render3d/nrrd_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

class NrrdFile : public testing::ScratchFolderTest {};

/// The samples `values` in the byte order of `big`.
template <typename T>
std::string samples(const std::vector<T>& values, bool big = false) {
  std::string s;
  for (const T v : values) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if (big) std::reverse(bytes, bytes + sizeof(T));
    s.append(bytes, sizeof(T));
  }
  return s;
}

/// A gzip stream holding `data` in one stored (uncompressed) deflate block (RFC 1951 3.2.4,
/// RFC 1952), with its CRC-32; `data` under 64 KiB.
std::string gzip_stored(const std::string& data) {
  std::string out("\x1f\x8b\x08\0\0\0\0\0\0\xff\x01", 11);
  out += samples(std::vector<uint16_t>{uint16_t(data.size()), uint16_t(~data.size())});
  out += data;
  uint32_t crc = 0xffffffffu;
  for (const char c : data) {
    crc ^= uint8_t(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return out + samples(std::vector<uint32_t>{~crc, uint32_t(data.size())});
}

/// The 3 x 2 x 2 uint8 volume's samples, voxel (i, j, k) = 10 + i + 3 j + 6 k.
std::string small_samples() {
  std::string s;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) s += char(10 + i + 3 * j + 6 * k);
  return s;
}

/// A header of the 3 x 2 x 2 uint8 volume, `fields` added before the blank line.
std::string small_header(const std::string& fields = "") {
  return "NRRD0005\n# a comment\ntype: uint8\ndimension: 3\nsizes: 3 2 2\nencoding: raw\n" +
         fields + "\n";
}

/// Checks `volume` is the 3 x 2 x 2 volume of small_samples().
void expect_small(const ScalarVolume& volume) {
  ASSERT_EQ(volume.nx, 3);
  ASSERT_EQ(volume.ny, 2);
  ASSERT_EQ(volume.nz, 2);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(volume.at(i, j, k), 10 + i + 3 * j + 6 * k) << i << ", " << j << ", " << k;
}

TEST_F(NrrdFile, ReadsSizesSpacingsAndValuesXFastest) {
  const ScalarVolume volume =
      load_nrrd(write("small.nrrd", small_header("spacings: 0.5 2 nan\nkey:=value: with colons\n") +
                                        small_samples()));
  expect_small(volume);
  EXPECT_EQ(volume.spacing, Eigen::Vector3d(0.5, 2, 1));  // nan: 1
}

TEST_F(NrrdFile, EveryTypeSpellingReadsItsValuesInEitherByteOrder) {
  auto read = [&](const std::string& type, const std::string& data, bool big) {
    const std::string endian = big ? "big" : "little";
    return load_nrrd(write("v.nrrd", "NRRD0004\ntype: " + type +
                                         "\ndimension: 3\nsizes: 2 1 2\nencoding: raw\nendian: " +
                                         endian + "\n\n" + data))
        .values;
  };
  const std::vector<int8_t> i8 = {-128, -1, 0, 127};
  const std::vector<uint8_t> u8 = {0, 1, 128, 255};
  const std::vector<int16_t> i16 = {-32768, -300, 7, 32767};
  const std::vector<uint16_t> u16 = {0, 300, 40000, 65535};
  const std::vector<int32_t> i32 = {std::numeric_limits<int32_t>::min(), -70000, 16777217, 5};
  const std::vector<uint32_t> u32 = {0, 70000, 3000000000u, 4294967295u};
  const std::vector<float> f32 = {-1.5f, 0.1f, 1e30f, 3};
  const std::vector<double> f64 = {-1.5, 0.1, 1e30, 123456789.125};
  for (const bool big : {false, true}) {
    for (const char* type : {"signed char", "int8", "int8_t"})
      EXPECT_EQ(read(type, samples(i8, big), big), std::vector<float>(i8.begin(), i8.end()))
          << type;
    for (const char* type : {"uchar", "unsigned char", "uint8", "uint8_t"})
      EXPECT_EQ(read(type, samples(u8, big), big), std::vector<float>(u8.begin(), u8.end()))
          << type;
    for (const char* type :
         {"short", "short int", "signed short", "signed short int", "int16", "int16_t"})
      EXPECT_EQ(read(type, samples(i16, big), big), std::vector<float>(i16.begin(), i16.end()))
          << type << " big " << big;
    for (const char* type :
         {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"})
      EXPECT_EQ(read(type, samples(u16, big), big), std::vector<float>(u16.begin(), u16.end()))
          << type << " big " << big;
    for (const char* type : {"int", "signed int", "int32", "int32_t"})
      EXPECT_EQ(read(type, samples(i32, big), big), std::vector<float>(i32.begin(), i32.end()))
          << type << " big " << big;
    for (const char* type : {"uint", "unsigned int", "uint32", "uint32_t"})
      EXPECT_EQ(read(type, samples(u32, big), big), std::vector<float>(u32.begin(), u32.end()))
          << type << " big " << big;
    EXPECT_EQ(read("float", samples(f32, big), big), f32) << "big " << big;
    EXPECT_EQ(read("double", samples(f64, big), big), std::vector<float>(f64.begin(), f64.end()))
        << "big " << big;
  }
}

// max_voxels bounds the volume read, named in the refusal: the 12 voxels are read at 12, refused
// at 11 from the header, and the limit must be at least 1.
TEST_F(NrrdFile, MaxVoxelsIsALimitThatNamesItself) {
  const std::string file = write("limit.nrrd", small_header() + small_samples());
  expect_small(load_nrrd(file, 12));
  EXPECT_NE(test::refusal([&] {
              load_nrrd(file, 11);
            }).find("(sizes: 3 2 2): 12 voxels, more than the 11 read (max_voxels"),
            std::string::npos);
  EXPECT_NE(test::refusal([&] { load_nrrd(file, 0); }).find("max_voxels must be >= 1"),
            std::string::npos);
}

TEST_F(NrrdFile, SpaceDirectionsGiveTheSpacingAsTheirLengths) {
  const ScalarVolume volume = load_nrrd(
      write("directions.nrrd", small_header("space: left-posterior-superior\nspace directions: "
                                            "(0,3,4) none (0, 0,-0.25)\nspace origin: (1,2,3)\n") +
                                   small_samples()));
  expect_small(volume);
  EXPECT_EQ(volume.spacing, Eigen::Vector3d(5, 1, 0.25));
}

TEST_F(NrrdFile, DetachedDataAndSkipsFindTheSamples) {
  // Detached, past a byte skip: the data file is named relative to the header's folder.
  write("samples.raw", "HEAD" + small_samples());
  const std::string detached = write("detached.nhdr", small_header("data file: samples.raw\n"
                                                                   "byte skip: 4\n"));
  EXPECT_EQ(nrrd_data_path(detached), path("samples.raw"));
  expect_small(load_nrrd(detached));
  // Attached: "byte skip: -1" takes the last bytes, "line skip" whole lines first.
  expect_small(load_nrrd(
      write("end.nrrd", small_header("byte skip: -1\n") + "junk\n\x01\x02" + small_samples())));
  expect_small(load_nrrd(
      write("lines.nrrd", small_header("line skip: 2\n") + "one\ntwo\n" + small_samples())));
  EXPECT_EQ(nrrd_data_path(path("end.nrrd")), "");  // attached
}

TEST_F(NrrdFile, GzipSamplesReadAsTheirRawTwin) {
  std::string header = small_header();
  header.replace(header.find("encoding: raw"), 13, "encoding: gzip");
  expect_small(load_nrrd(write("attached.nrrd", header + gzip_stored(small_samples()))));
  write("samples.raw.gz", gzip_stored(small_samples()));
  header.replace(header.find("encoding: gzip"), 14, "encoding: gz");
  header.insert(header.size() - 1, "datafile: samples.raw.gz\n");
  expect_small(load_nrrd(write("detached.nhdr", header)));
}

// Gzip data: the byte skip skips bytes of the inflated data, attached or detached (the NRRD
// format's rule; the skip was ignored); a skip past them is refused, and -1, read only with raw.
TEST_F(NrrdFile, AByteSkipSkipsGzipDataAfterItIsInflated) {
  auto gzip_header = [](const std::string& fields) {
    std::string header = small_header(fields);
    return header.replace(header.find("encoding: raw"), 13, "encoding: gzip");
  };
  expect_small(load_nrrd(write(
      "attached.nrrd", gzip_header("byte skip: 4\n") + gzip_stored("HEAD" + small_samples()))));
  write("samples.raw.gz", gzip_stored("HEAD" + small_samples()));
  expect_small(
      load_nrrd(write("detached.nhdr", gzip_header("data file: samples.raw.gz\nbyte skip: 4\n"))));
  const std::pair<std::string, std::string> cases[] = {
      {"byte skip: 20\n", "the byte skip (20) is beyond the end of the gzip data (12 bytes)"},
      {"byte skip: 2\n", "the gzip data holds 10 bytes after the byte skip"},
      {"byte skip: -1\n", "(byte skip: -1): -1 is read only with raw encoding"},
      {"byte skip: -2\n", "(byte skip: -2): not a byte count"},
      {"byte skip: 2000000000\n",
       "(byte skip: 2000000000): with the samples, more than the 1074790400 bytes of data read"},
  };
  for (const auto& [fields, what] : cases) {
    const std::string file = write("bad.nrrd", gzip_header(fields) + gzip_stored(small_samples()));
    const std::string message = test::refusal([&] { load_nrrd(file); });
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
  }
}

TEST_F(NrrdFile, RefusesBadHeadersAndShortDataNamingTheFileAndTheLine) {
  const std::string data = small_samples();
  const std::string good = small_header() + data;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::pair<std::string, std::string> cases[] = {
      {"NRRD0006" + good.substr(8), "not a NRRD file"},
      {replaced("sizes: 3 2 2", "sizes 3 2 2"),
       "header line 5 'sizes 3 2 2' is not 'field: value'"},
      {replaced("type: uint8\n", ""), "the header has no 'type' field"},
      {replaced("dimension: 3\n", ""), "the header has no 'dimension' field"},
      {replaced("type: uint8", "type: int64"), "header line 3 (type: int64): unknown type"},
      {replaced("dimension: 3", "dimension: 4"), "header line 4 (dimension: 4): only 3D volumes"},
      {replaced("sizes: 3 2 2", "sizes: 3 2"), "header line 5 (sizes: 3 2): expected three sizes"},
      {replaced("sizes: 3 2 2", "sizes: 3 0 2"), "a volume of zero size"},
      {replaced("encoding: raw", "encoding: ascii"), "(encoding: ascii): only raw and gzip"},
      {replaced("type: uint8", "type: short"), "the header has no 'endian' field"},
      {small_header("spacings: 1 -1 1\n") + data, "(spacings: 1 -1 1): a spacing that is not"},
      {small_header("space directions: (0,0,0) (1,0,0) (0,1,0)\n") + data, "a zero direction"},
      // Numbers are read whole: '2x' is not 2, nor is a fourth spacing or vector ignored.
      {small_header("spacings: 1 2x 1\n") + data, "(spacings: 1 2x 1): a spacing that is not a"},
      {small_header("spacings: 1 1 1 7\n") + data, "(spacings: 1 1 1 7): expected three"},
      {small_header("space directions: (1,0,0) (0,1y,0) (0,0,1)\n") + data,
       "a vector component that is not a number"},
      {small_header("space directions: (1,0,0) (0,1,0) (0,0,1) (1,1,1)\n") + data,
       "expected three (x,y,z) vectors"},
      {good.substr(0, good.size() - 5),
       "the header claims 3 x 2 x 2 uint8 voxels (12 bytes), the data holds 7 bytes"},
      {small_header("byte skip: 3\n") + data, "the data holds 9 bytes"},
      {small_header("byte skip: lots\n") + data, "(byte skip: lots): not -1 or a byte count"},
      {small_header("line skip: 2.5\n") + data, "(line skip: 2.5): not a line count"},
      {small_header().substr(0, small_header().size() - 1), "no data"},
      // Control characters of a header line are quoted, not sent to the terminal.
      {replaced("sizes: 3 2 2", "sizes\x1b[31m 3 2 2"),
       "header line 5 'sizes\\x1b[31m 3 2 2' is not 'field: value'"},
      {replaced("type: uint8", "type: \x1b[31muint8"),
       "header line 3 (type: \\x1b[31muint8): unknown type"},
      {small_header("data file: a\x1b[31m.raw\n"),
       "data file 'a\\x1b[31m.raw': a file name with control characters"},
  };
  int i = 0;
  for (const auto& [bytes, what] : cases) {
    const std::string file = write("bad" + std::to_string(i++) + ".nrrd", bytes);
    const std::string message = test::refusal([&] { load_nrrd(file); });
    EXPECT_EQ(message.rfind("load_nrrd: '" + file + "'", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
  }
  // A missing detached data file: the message names the header and the data file.
  const std::string lost = write("lost.nhdr", small_header("data file: gone.raw\n"));
  const std::string gone = test::refusal([&] { load_nrrd(lost); });
  EXPECT_NE(gone.find("'" + lost + "': data file '" + path("gone.raw") + "' does not exist"),
            std::string::npos)
      << gone;
  // Short detached data: the message names the header and the data file.
  write("short.raw", data.substr(0, 5));
  const std::string header = write("short.nhdr", small_header("data file: short.raw\n"));
  const std::string message = test::refusal([&] { load_nrrd(header); });
  EXPECT_NE(message.find("'" + header + "': data file '" + path("short.raw") + "'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("holds 5 bytes"), std::string::npos) << message;
}

}  // namespace
}  // namespace geolens
