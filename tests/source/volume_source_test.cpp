// The volume source: a sphere phantom written by the test as NRRD (raw and gzip) and NIfTI
// (.nii and .nii.gz) reads back the same, renders as a disk of the radius the camera gives with
// the ct preset (so the anisotropic spacing is respected), tiles are renders of their region,
// and bad files and transfer functions are refused with one line naming them.

#include "source/volume_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/source/source_file.h"
#include "render3d/nifti_file.h"
#include "render3d/nrrd_file.h"
#include "support/refusal.h"
#include "support/scratch_folder.h"

namespace {

using geolens::Image;
using geolens::InvalidInput;
using geolens::ScalarVolume;

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

template <typename T>
void put(std::string& s, size_t offset, T value) {
  if (s.size() < offset + sizeof(T)) s.resize(offset + sizeof(T), '\0');
  std::memcpy(s.data() + offset, &value, sizeof(T));
}

/// A gzip file holding `data` in stored (uncompressed) deflate blocks (RFC 1951 section 3.2.4,
/// RFC 1952), with its CRC-32.
std::string gzip_stored(const std::string& data) {
  std::string out("\x1f\x8b\x08\0\0\0\0\0\0\xff", 10);
  size_t at = 0;
  do {
    const size_t n = std::min<size_t>(data.size() - at, 65535);
    out += char(at + n == data.size() ? 1 : 0);
    put(out, out.size(), uint16_t(n));
    put(out, out.size(), uint16_t(~n));
    out += data.substr(at, n);
    at += n;
  } while (at < data.size());
  uint32_t crc = 0xffffffffu;
  for (const char c : data) {
    crc ^= uint8_t(c);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  put(out, out.size(), ~crc);
  put(out, out.size(), uint32_t(data.size()));
  return out;
}

constexpr int kNx = 40, kNy = 40, kNz = 20;  // spacing 1 x 1 x 2 mm: a 40 mm cube
constexpr double kRadius = 12;               // mm

/// The phantom's int16 samples, x fastest: 1000 HU inside a sphere of kRadius mm around the
/// box's centre, -1000 outside, a 2 mm linear ramp between (so the 0 HU surface is the sphere).
std::vector<int16_t> phantom() {
  std::vector<int16_t> v;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        const double r =
            std::sqrt(std::pow(i - 19.5, 2) + std::pow(j - 19.5, 2) + std::pow(2 * k - 19.0, 2));
        v.push_back(int16_t(2 * std::lround(500 * std::clamp(kRadius - r, -1.0, 1.0))));
      }
  return v;
}

std::string samples(const std::vector<int16_t>& v, int16_t divide = 1) {
  std::string s(v.size() * 2, '\0');
  for (size_t i = 0; i < v.size(); ++i) put(s, 2 * i, int16_t(v[i] / divide));
  return s;
}

std::string nrrd_header(const std::string& encoding, int nz = kNz) {
  return "NRRD0004\n# a sphere phantom\ntype: short\ndimension: 3\nsizes: 40 40 " +
         std::to_string(nz) + "\nspacings: 1 1 2\nencoding: " + encoding +
         "\nendian: little\nkey:=value\n\n";
}

/// A NIfTI-1 single file: 348-byte header, 4 bytes of extension flag, int16 data stored as half
/// the values with scl_slope 2.
std::string nifti(const std::vector<int16_t>& v, int nz = kNz) {
  std::string h(352, '\0');
  put(h, 0, int32_t(348));
  const int16_t dim[8] = {3, kNx, kNy, int16_t(nz), 1, 1, 1, 1};
  for (int k = 0; k < 8; ++k) put(h, 40 + 2 * k, dim[k]);
  put(h, 70, int16_t(4));   // DT_SIGNED_SHORT
  put(h, 72, int16_t(16));  // bitpix
  const float pixdim[8] = {1, 1, 1, 2, 1, 1, 1, 1};
  for (int k = 0; k < 8; ++k) put(h, 76 + 4 * k, pixdim[k]);
  put(h, 108, 352.0f);  // vox_offset
  put(h, 112, 2.0f);    // scl_slope
  put(h, 116, 0.0f);    // scl_inter
  std::memcpy(h.data() + 344, "n+1\0", 4);
  return h + samples(v, 2);
}

class VolumeSourceTest : public geolens::testing::ScratchFolderTest {
 protected:
  void write_all() {
    const std::vector<int16_t> v = phantom();
    write(path("raw.nrrd"), nrrd_header("raw") + samples(v));
    write(path("gzip.nrrd"), nrrd_header("gzip") + gzip_stored(samples(v)));
    write(path("plain.nii"), nifti(v));
    write(path("packed.nii.gz"), gzip_stored(nifti(v)));
  }
};

TEST_F(VolumeSourceTest, NrrdAndNiftiReadTheSamePhantom) {
  write_all();
  const std::vector<int16_t> v = phantom();
  for (const char* name : {"raw.nrrd", "gzip.nrrd", "plain.nii", "packed.nii.gz"}) {
    const ScalarVolume volume = std::string(name).find(".nii") != std::string::npos
                                    ? geolens::load_nifti(path(name))
                                    : geolens::load_nrrd(path(name));
    EXPECT_EQ(volume.nx, kNx) << name;
    EXPECT_EQ(volume.ny, kNy) << name;
    EXPECT_EQ(volume.nz, kNz) << name;
    EXPECT_EQ(volume.spacing, Eigen::Vector3d(1, 1, 2)) << name;
    ASSERT_EQ(volume.values.size(), v.size()) << name;
    size_t differ = 0;
    for (size_t i = 0; i < v.size(); ++i) differ += volume.values[i] != float(v[i]);
    EXPECT_EQ(differ, 0u) << name;
    EXPECT_EQ(volume.at(19, 19, 10), 1000) << name;
    EXPECT_EQ(volume.at(0, 0, 0), -1000) << name;
  }
}

TEST_F(VolumeSourceTest, CtPresetShowsTheSphereWhereTheCameraPutsIt) {
  write_all();
  geolens::SourceFileOptions options;
  options.width = options.height = 160;
  options.view = "0,0";
  options.transfer = "ct";
  std::vector<std::vector<uint8_t>> pictures;
  for (const char* name : {"raw.nrrd", "gzip.nrrd", "plain.nii", "packed.nii.gz"}) {
    const geolens::SourceFile file = geolens::open_source(path(name), options);
    EXPECT_EQ(file.kind, "volume") << name;
    EXPECT_EQ(file.scale, 4) << name;
    const geolens::TexelRegion frame = file.source->fetch(2, 0, 0, 160, 160);
    std::vector<uint8_t> pixels;
    for (int y = 0; y < 160; ++y)
      pixels.insert(pixels.end(), frame.at(0, y), frame.at(0, y) + 160 * 3);
    pictures.push_back(pixels);
  }
  for (size_t i = 1; i < pictures.size(); ++i) EXPECT_EQ(pictures[i], pictures[0]) << i;

  // The silhouette of a sphere of radius R seen from distance d is a disk of radius
  // focal tan(asin(R / d)) around the frame's centre; an ellipse if the 2 mm slices were taken
  // for 1 mm. The phantom's bone (>= 400 HU) starts 0.4 mm inside R.
  geolens::OrbitCamera camera = geolens::VolumeSourceOptions{}.camera;
  camera.azimuth_degrees = camera.elevation_degrees = 0;
  const double box_radius = std::sqrt(40.0 * 40 * 3) / 2;
  const geolens::Projection p =
      geolens::place_camera(camera, Eigen::Vector3d(19.5, 19.5, 19), box_radius, 160, 160);
  const double d = (p.eye - Eigen::Vector3d(19.5, 19.5, 19)).norm();
  const double expected = p.focal * std::tan(std::asin((kRadius - 0.3) / d));
  auto lit = [&](int x, int y) {
    const uint8_t* px = &pictures[0][(size_t(y) * 160 + size_t(x)) * 3];
    return px[0] + px[1] + px[2] > 3 * 60;
  };
  int across = 0, down = 0;
  for (int i = 0; i < 160; ++i) {
    across += lit(i, 80);
    down += lit(80, i);
  }
  std::printf("sphere silhouette: %d px across, %d px down, expected %.1f\n", across, down,
              2 * expected);
  EXPECT_NEAR(across, 2 * expected, 2.5);
  EXPECT_NEAR(down, 2 * expected, 2.5);
  EXPECT_FALSE(lit(80 - int(expected) - 4, 80));  // outside: background
  EXPECT_FALSE(lit(5, 5));
  // Bone is white: the centre is bright and neutral.
  const uint8_t* centre = &pictures[0][(80 * 160 + 80) * 3];
  EXPECT_GT(centre[0], 150);
  EXPECT_NEAR(centre[0], centre[2], 40);
}

TEST_F(VolumeSourceTest, TilesAreDirectRendersAndATableColoursTheSphere) {
  write_all();
  write(path("red.tf"), "# value R G B opacity\n-1000 0 0 0 0\n0 0 0 0 0\n500 255 0 0 1\n");
  geolens::VolumeSourceOptions options;
  options.tiling.tile_size = 64;
  const ScalarVolume volume = geolens::load_nrrd(path("raw.nrrd"));
  const geolens::TransferFunction red = geolens::load_transfer_table(path("red.tf"));
  const geolens::SourceFile file = geolens::volume_source(volume, red, 48, 40, options);
  const geolens::VolumeRenderer direct(volume, red, options.camera, 48, 40, options.style);
  // Level-0 texels [50, 150) x [30, 110): 3 x 2 tiles of 64.
  const geolens::TexelRegion texels = file.source->fetch(0, 50, 30, 100, 80);
  const Image region = direct.render({0.25, 50, 30, 100, 80});
  size_t differ = 0, red_pixels = 0;
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 100; ++x)
      for (int c = 0; c < 3; ++c) {
        differ += texels.at(50 + x, 30 + y)[c] != region.at(x, y)[c];
        red_pixels += c == 0 && region.at(x, y)[0] > 100 && region.at(x, y)[1] < 30;
      }
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(red_pixels, 1000u);  // the sphere fills much of the centre, in red
  const auto counters = file.counters();
  EXPECT_EQ(counters[0].first, "tiles_rendered");
  EXPECT_EQ(counters[0].second, 6);
}

using geolens::test::refusal;

TEST_F(VolumeSourceTest, RefusesBadVolumesAndTransfersWithOneLineNamingTheFile) {
  write_all();
  const std::vector<int16_t> v = phantom();
  auto expect = [&](const std::string& name, const std::string& what,
                    const geolens::SourceFileOptions& options = {}, std::string named = "") {
    const std::string message = refusal([&] { geolens::open_source(path(name), options); });
    EXPECT_NE(message.find(path(name)), std::string::npos) << name << ": " << message;
    if (!named.empty()) EXPECT_NE(message.find(named), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  write(path("zero.nrrd"), nrrd_header("raw", 0));
  expect("zero.nrrd", "a volume of zero size");
  write(path("short.nrrd"), nrrd_header("raw") + samples(v).substr(0, 1000));
  expect("short.nrrd",
         "the header claims 40 x 40 x 20 int16 voxels (64000 bytes), the data holds 1000 bytes");
  const std::string gz = gzip_stored(samples(v));
  write(path("short_gz.nrrd"), nrrd_header("gzip") + gz.substr(0, gz.size() / 2));
  expect("short_gz.nrrd",
         "the header claims 40 x 40 x 20 int16 voxels (64000 bytes), the gzip data holds");
  write(path("corrupt.nrrd"), nrrd_header("gzip") + std::string(100, 'x'));
  expect("corrupt.nrrd", "corrupt gzip data");
  write(path("magic.nrrd"), "NRRX0004\n");
  expect("magic.nrrd", "not a NRRD file");
  write(path("type.nrrd"), "NRRD0004\ntype: complex\ndimension: 3\n\n");
  expect("type.nrrd", "header line 2 (type: complex): unknown type");
  write(path("short.nii"), nifti(v).substr(0, 352 + 5000));
  expect("short.nii",
         "the header claims 40 x 40 x 20 int16 voxels (64000 bytes), the file holds 5000 bytes");
  write(path("short.nii.gz"), gzip_stored(nifti(v).substr(0, 352 + 5000)));
  expect("short.nii.gz",
         "the header claims 40 x 40 x 20 int16 voxels (64000 bytes), the file holds 5000 bytes");
  write(path("zero.nii"), nifti({}, 0));
  expect("zero.nii", "a volume of zero size");
  // A vox_offset past 2^31 (libnifti read from byte 348 instead).
  std::string far = nifti(v);
  put(far, 108, 3e9f);
  write(path("far.nii"), far);
  expect("far.nii", "is negative or beyond 2^31 bytes");
  write(path("tiny.nii"), "not a nifti");
  expect("tiny.nii", "not a NIfTI-1 file");

  geolens::SourceFileOptions options;
  options.transfer = "bone";
  expect("raw.nrrd", "unknown transfer 'bone': not a preset (ct, mri) or a table file", options);
  write(path("bad.tf"), "0 0 0 0 0\n-5 255 255 255 1\n");
  options.transfer = path("bad.tf");
  expect("raw.nrrd", "line 2: the values must increase", options, path("bad.tf"));
  options.view = "north";
  options.transfer = "ct";
  expect("raw.nrrd", "is not AZ,EL", options);
}

}  // namespace
