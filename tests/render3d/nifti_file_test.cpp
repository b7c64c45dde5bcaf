// The NIfTI-1 reader on tiny volumes the test writes by hand (a 348-byte header, 4 bytes of
// extension flag, the samples at vox_offset 352): dimensions, spacing and values x fastest, every
// voxel type read converts to its value, scl_slope / scl_inter scale unless the slope is zero, a
// 4D file gives its first volume, a big-endian file reads as its little-endian twin, and bad or
// truncated files are refused with InvalidInput naming load_nifti and the file.

#include "render3d/nifti_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

// NIfTI-1 datatype codes (nifti1.h).
constexpr int16_t kUint8 = 2, kInt16 = 4, kInt32 = 8, kFloat32 = 16, kComplex64 = 32, kFloat64 = 64,
                  kInt8 = 256, kUint16 = 512, kUint32 = 768, kInt64 = 1024;

/// Bytes in the order of a little- or big-endian file.
class Bytes {
 public:
  explicit Bytes(bool big) : big_(big) {}
  template <typename T>
  void put(size_t offset, T value) {
    if (text.size() < offset + sizeof(T)) text.resize(offset + sizeof(T), '\0');
    char* at = text.data() + offset;
    std::memcpy(at, &value, sizeof(T));
    if (big_) std::reverse(at, at + sizeof(T));
  }
  template <typename T>
  void append(T value) {
    put(text.size(), value);
  }
  std::string text;

 private:
  bool big_;
};

/// What the header says.
struct Header {
  std::array<int16_t, 8> dim = {3, 1, 1, 1, 1, 1, 1, 1};
  int16_t datatype = kUint8, bitpix = 8;
  std::array<float, 8> pixdim = {1, 1, 1, 1, 1, 1, 1, 1};
  float vox_offset = 352, scl_slope = 0, scl_inter = 0;
};

/// A single-file NIfTI-1 (.nii): the header, then `samples` at vox_offset.
template <typename T>
std::string nifti(const Header& h, const std::vector<T>& samples, bool big = false) {
  Bytes b(big);
  b.put(0, int32_t(348));
  for (int k = 0; k < 8; ++k) b.put(40 + 2 * k, h.dim[size_t(k)]);
  b.put(70, h.datatype);
  b.put(72, h.bitpix);
  for (int k = 0; k < 8; ++k) b.put(76 + 4 * k, h.pixdim[size_t(k)]);
  b.put(108, h.vox_offset);
  b.put(112, h.scl_slope);
  b.put(116, h.scl_inter);
  b.text.resize(352, '\0');
  std::memcpy(b.text.data() + 344, "n+1\0", 4);
  for (const T v : samples) b.append(v);
  return b.text;
}

class NiftiFile : public testing::ScratchFolderTest {
 public:
  using ScratchFolderTest::write;  // for read_as below
};

/// A 3 x 2 x 2 uint8 header and its values, voxel (i, j, k) = 10 + i + 3 j + 6 k.
Header small_header() {
  Header h;
  h.dim = {3, 3, 2, 2, 1, 1, 1, 1};
  return h;
}
std::vector<uint8_t> small_values() {
  std::vector<uint8_t> v;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) v.push_back(uint8_t(10 + i + 3 * j + 6 * k));
  return v;
}

TEST_F(NiftiFile, ReadsDimensionsSpacingAndValuesXFastest) {
  Header h = small_header();
  h.pixdim = {1, 0.5f, 2, 3, 1, 1, 1, 1};
  const ScalarVolume volume = load_nifti(write("small.nii", nifti(h, small_values())));
  EXPECT_EQ(volume.nx, 3);
  EXPECT_EQ(volume.ny, 2);
  EXPECT_EQ(volume.nz, 2);
  EXPECT_EQ(volume.spacing, Eigen::Vector3d(0.5, 2, 3));
  ASSERT_EQ(volume.values.size(), 12u);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(volume.at(i, j, k), 10 + i + 3 * j + 6 * k) << i << ", " << j << ", " << k;
  // The spacing is |pixdim|, 1 where it is 0.
  h.pixdim = {-1, -2, 0, 0.25f, 1, 1, 1, 1};
  EXPECT_EQ(load_nifti(write("flipped.nii", nifti(h, small_values()))).spacing,
            Eigen::Vector3d(2, 1, 0.25));
}

/// Reads `values` written as a 2 x 2 x 1 volume of `datatype` and returns what was read.
template <typename T>
std::vector<float> read_as(NiftiFile& test, const std::string& name, int16_t datatype,
                           const std::vector<T>& values, bool big = false) {
  Header h;
  h.dim = {3, 2, 2, 1, 1, 1, 1, 1};
  h.datatype = datatype;
  h.bitpix = int16_t(8 * sizeof(T));
  return load_nifti(test.write(name, nifti(h, values, big))).values;
}

/// `values` each converted to float.
template <typename T>
std::vector<float> as_float(const std::vector<T>& values) {
  return std::vector<float>(values.begin(), values.end());
}

// max_voxels bounds the volume read, named in the refusal, as load_nrrd's.
TEST_F(NiftiFile, MaxVoxelsIsALimitThatNamesItself) {
  const std::string file = write("limit.nii", nifti(small_header(), small_values()));
  EXPECT_EQ(load_nifti(file, 12).values.size(), 12u);
  EXPECT_NE(test::refusal([&] {
              load_nifti(file, 11);
            }).find("3 x 2 x 2: 12 voxels, more than the 11 read (max_voxels"),
            std::string::npos);
}

TEST_F(NiftiFile, EveryVoxelTypeReadsItsValuesAsFloats) {
  using L8 = std::numeric_limits<int8_t>;
  using L16 = std::numeric_limits<int16_t>;
  using L32 = std::numeric_limits<int32_t>;
  const std::vector<int8_t> i8 = {L8::min(), -1, 0, L8::max()};
  const std::vector<uint8_t> u8 = {0, 1, 128, 255};
  const std::vector<int16_t> i16 = {L16::min(), -300, 7, L16::max()};
  const std::vector<uint16_t> u16 = {0, 300, 40000, 65535};
  const std::vector<int32_t> i32 = {L32::min(), -70000, 16777217, L32::max()};
  const std::vector<uint32_t> u32 = {0, 70000, 3000000000u, 4294967295u};
  const std::vector<float> f32 = {-1.5f, 0.1f, 1e30f, -0.0f};
  const std::vector<double> f64 = {-1.5, 0.1, 1e30, 123456789.125};
  for (const bool big : {false, true}) {
    const std::string e = big ? "_be" : "_le";
    EXPECT_EQ(read_as(*this, "i8" + e + ".nii", kInt8, i8, big), as_float(i8));
    EXPECT_EQ(read_as(*this, "u8" + e + ".nii", kUint8, u8, big), as_float(u8));
    EXPECT_EQ(read_as(*this, "i16" + e + ".nii", kInt16, i16, big), as_float(i16));
    EXPECT_EQ(read_as(*this, "u16" + e + ".nii", kUint16, u16, big), as_float(u16));
    EXPECT_EQ(read_as(*this, "i32" + e + ".nii", kInt32, i32, big), as_float(i32));
    EXPECT_EQ(read_as(*this, "u32" + e + ".nii", kUint32, u32, big), as_float(u32));
    EXPECT_EQ(read_as(*this, "f32" + e + ".nii", kFloat32, f32, big), as_float(f32));
    EXPECT_EQ(read_as(*this, "f64" + e + ".nii", kFloat64, f64, big), as_float(f64));
  }
}

TEST_F(NiftiFile, SlopeAndInterceptScaleTheValuesUnlessTheSlopeIsZero) {
  Header h = small_header();
  h.scl_slope = 0.5f;
  h.scl_inter = -10;
  const ScalarVolume scaled = load_nifti(write("scaled.nii", nifti(h, small_values())));
  EXPECT_EQ(scaled.at(0, 0, 0), 10 * 0.5f - 10);
  EXPECT_EQ(scaled.at(2, 1, 1), 21 * 0.5f - 10);
  h.scl_slope = 0;  // "no scaling", whatever the intercept
  h.scl_inter = 100;
  const ScalarVolume raw = load_nifti(write("raw.nii", nifti(h, small_values())));
  EXPECT_EQ(raw.at(2, 1, 1), 21);
}

TEST_F(NiftiFile, AFourDimensionalFileGivesItsFirstVolume) {
  Header h;
  h.dim = {4, 2, 2, 1, 3, 1, 1, 1};
  h.datatype = kInt16;
  h.bitpix = 16;
  std::vector<int16_t> v;
  for (int t = 0; t < 3; ++t)
    for (int i = 0; i < 4; ++i) v.push_back(int16_t(100 * t + i));
  const ScalarVolume volume = load_nifti(write("series.nii", nifti(h, v)));
  EXPECT_EQ(volume.nz, 1);
  EXPECT_EQ(volume.values, (std::vector<float>{0, 1, 2, 3}));
}

TEST_F(NiftiFile, RefusesBadAndTruncatedFilesNamingTheFile) {
  auto refused = [&](const std::string& name, const std::string& bytes) {
    const std::string file = write(name, bytes);
    const std::string message = test::refusal([&] { load_nifti(file); });
    EXPECT_EQ(message.rfind("load_nifti: '" + file + "': ", 0), 0u) << message;
    return message;
  };
  auto expect_says = [](const std::string& message, const std::string& what) {
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
  };
  const std::string good = nifti(small_header(), small_values());
  expect_says(refused("header.nii", good.substr(0, 200)),
              "not a NIfTI-1 file (200 bytes, fewer than its 348-byte header)");
  std::string wrong_size = good;
  wrong_size[0] = char(100);
  expect_says(refused("size.nii", wrong_size), "its header size is not 348");
  Header h = small_header();
  h.dim[0] = 0;
  expect_says(refused("rank.nii", nifti(h, small_values())), "bad dim[0] = 0");
  h = small_header();
  h.dim[2] = 0;
  expect_says(refused("zero.nii", nifti(h, small_values())), "a volume of zero size (dim[2] = 0)");
  h = small_header();
  h.datatype = kComplex64;
  h.bitpix = 64;
  expect_says(refused("complex.nii", nifti(h, std::vector<double>(12))),
              "voxel type COMPLEX64 is not read");
  h.datatype = kInt64;
  expect_says(refused("int64.nii", nifti(h, std::vector<int64_t>(12))),
              "voxel type INT64 is not read");
  expect_says(refused("truncated.nii", good.substr(0, 352 + 7)),
              "the header claims 3 x 2 x 2 uint8 voxels (12 bytes), the file holds 7 bytes");
  h = small_header();
  h.vox_offset = -8;
  expect_says(refused("offset.nii", nifti(h, small_values())), "vox_offset");
  const std::string nowhere = path("nowhere.nii");
  EXPECT_NE(test::refusal([&] { load_nifti(nowhere); }).find("'" + nowhere + "': no such file"),
            std::string::npos);
  std::filesystem::create_directory(path("folder.nii"));
  EXPECT_NE(test::refusal([&] { load_nifti(path("folder.nii")); }).find("not a file"),
            std::string::npos);
}

}  // namespace
}  // namespace geolens
