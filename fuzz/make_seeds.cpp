// Writes the seed corpus of the fuzz targets: `make_fuzz_seeds DIR` makes DIR/<kind>/ for each
// target with a few tiny inputs, valid ones (each kind's variants: colour types and depths,
// encodings, byte orders, layouts) and invalid ones (truncated, out of range, malformed). PNG and
// JPEG files come from the library's own encoders, or, for what they do not write (16-bit and
// palette PNG), from chunks assembled here; gzip from zlib. fuzz/corpus/ was made so, then the
// inputs of past findings were added beside these (named regression-*).
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geolens/io/image.h"

namespace {

namespace fs = std::filesystem;
using Bytes = std::string;

fs::path out_dir;

void write(const std::string& kind, const std::string& name, const Bytes& bytes) {
  fs::create_directories(out_dir / kind);
  std::ofstream(out_dir / kind / name, std::ios::binary) << bytes;
}

Bytes read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

/// `image` encoded by save_image (PNG or JPEG by `extension`).
Bytes encoded(const geolens::Image& image, const std::string& extension) {
  const fs::path path = fs::temp_directory_path() / ("geolens-seed" + extension);
  geolens::save_image(path.string(), image);
  Bytes bytes = read(path);
  fs::remove(path);
  return bytes;
}

geolens::Image pattern(int width, int height, int channels) {
  geolens::Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y)[c] = uint8_t(x * 37 + y * 11 + c * 71);
  return image;
}

Bytes big_endian32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

Bytes chunk(const std::string& type, const Bytes& data) {
  const Bytes body = type + data;
  const uint32_t crc =
      uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
  return big_endian32(uint32_t(data.size())) + body + big_endian32(crc);
}

Bytes deflated(const Bytes& raw, int window_bits) {
  z_stream stream{};
  deflateInit2(&stream, 9, Z_DEFLATED, window_bits, 8, Z_DEFAULT_STRATEGY);
  Bytes out(deflateBound(&stream, uLong(raw.size())) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  stream.avail_in = uInt(raw.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = uInt(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

Bytes zlib(const Bytes& raw) { return deflated(raw, 15); }
Bytes gzip(const Bytes& raw) { return deflated(raw, 15 + 16); }

/// A PNG of `width` x `height`, colour type `colour`, `depth` bits, the given filtered rows (a
/// filter byte 0 then the samples, per row) and extra chunks before IDAT.
Bytes png(int width, int height, int depth, int colour, const Bytes& rows,
          const Bytes& before_data = "") {
  Bytes ihdr = big_endian32(uint32_t(width)) + big_endian32(uint32_t(height));
  ihdr += char(depth);
  ihdr += char(colour);
  ihdr += Bytes(3, '\0');
  return Bytes("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + before_data +
         chunk("IDAT", zlib(rows)) + chunk("IEND", "");
}

template <class T>
Bytes raw_of(const T& value) {
  return Bytes(reinterpret_cast<const char*>(&value), sizeof value);
}

/// A NIfTI-1 single file (magic n+1, data at byte 352) of nx x ny x nz voxels of `datatype`
/// (`bitpix` bits) holding `data`.
Bytes nifti(int16_t nx, int16_t ny, int16_t nz, int16_t datatype, int16_t bitpix, const Bytes& data,
            float slope = 0, float inter = 0, int16_t dims = 3) {
  Bytes header(348, '\0');
  auto put = [&](size_t at, const Bytes& bytes) { header.replace(at, bytes.size(), bytes); };
  put(0, raw_of(int32_t(348)));
  const int16_t dim[8] = {dims, nx, ny, nz, 1, 1, 1, 1};
  put(40, Bytes(reinterpret_cast<const char*>(dim), sizeof dim));
  put(70, raw_of(datatype));
  put(72, raw_of(bitpix));
  const float pixdim[8] = {1, 1.5f, 1, 2, 1, 1, 1, 1};
  put(76, Bytes(reinterpret_cast<const char*>(pixdim), sizeof pixdim));
  put(108, raw_of(352.0f));
  put(112, raw_of(slope));
  put(116, raw_of(inter));
  put(344, Bytes("n+1\0", 4));
  return header + Bytes(4, '\0') + data;
}

Bytes counting(size_t n, int step = 1) {
  Bytes b(n, '\0');
  for (size_t i = 0; i < n; ++i) b[i] = char(i * size_t(step));
  return b;
}

void images() {
  using geolens::Image;
  write("image", "grey_1x1.png", encoded(pattern(1, 1, 1), ".png"));
  write("image", "grey_alpha_2x2.png", encoded(pattern(2, 2, 2), ".png"));
  write("image", "rgb_3x2.png", encoded(pattern(3, 2, 3), ".png"));
  write("image", "rgba_4x4.png", encoded(pattern(4, 4, 4), ".png"));
  write("image", "rgb_8x8.jpg", encoded(pattern(8, 8, 3), ".jpg"));
  write("image", "grey_5x3.jpg", encoded(pattern(5, 3, 1), ".jpg"));
  // 16-bit grey, 2 x 2.
  write("image", "grey16_2x2.png",
        png(2, 2, 16, 0, Bytes("\0\x00\x01\xff\xff", 5) + Bytes("\0\x80\x00\x12\x34", 5)));
  // A palette of 3 with transparency, 4 x 1 at 2 bits (indices 0 1 2 0).
  write("image", "palette_trns_4x1.png",
        png(4, 1, 2, 3, Bytes("\0\x18", 2),
            chunk("PLTE", Bytes("\xff\0\0\0\xff\0\0\0\xff", 9)) + chunk("tRNS", Bytes("\x80", 1))));
  // Invalid: cut inside the data; a bad CRC; a JPEG cut after its header; not an image.
  const Bytes whole = encoded(pattern(4, 4, 3), ".png");
  write("image", "truncated.png", whole.substr(0, whole.size() - 20));
  Bytes bad_crc = whole;
  bad_crc[30] = char(bad_crc[30] ^ 0x55);
  write("image", "bad_crc.png", bad_crc);
  const Bytes jpeg = encoded(pattern(8, 8, 3), ".jpg");
  write("image", "truncated.jpg", jpeg.substr(0, jpeg.size() / 2));
  write("image", "text.txt", "not an image\n");
}

void masks() {
  geolens::Image blob(16, 16, 1);
  for (int y = 3; y < 12; ++y)
    for (int x = 4; x < 13; ++x) *blob.at(x, y) = 255;
  write("mask", "blob_16x16.png", encoded(blob, ".png"));
  for (int y = 6; y < 9; ++y)
    for (int x = 7; x < 10; ++x) *blob.at(x, y) = 0;
  write("mask", "ring_16x16.png", encoded(blob, ".png"));
  geolens::Image two(12, 8, 1);
  for (int y = 1; y < 5; ++y)
    for (int x = 1; x < 5; ++x) *two.at(x, y) = 200;
  *two.at(10, 6) = 1;  // a speck
  write("mask", "blob_and_speck.jpg", encoded(two, ".jpg"));
  // A 16-bit mask of value 1 (non-zero at its depth), 4 x 4.
  Bytes rows;
  for (int y = 0; y < 4; ++y) rows += Bytes(1, '\0') + Bytes("\0\x01\0\x01\0\x01\0\x01", 8);
  write("mask", "grey16_ones.png", png(4, 4, 16, 0, rows));
  write("mask", "empty_4x4.png", encoded(geolens::Image(4, 4, 1), ".png"));
}

void text_kinds() {
  write("polygon", "square.txt", "10 10\n200 10\n200 200\n10 200\n");
  write("polygon", "commas_comments.txt", "# a triangle\n20,20\n100, 30 # two\n50;120\n20 20\n");
  write("polygon", "bowtie.txt", "10 10\n100 100\n100 10\n10 100\n");
  write("polygon", "outside.txt", "-5 10\n300 10\n300 300\n");
  write("polygon", "bad_line.txt", "1 2\n3 x\n");
  write("polygon", "two_points.txt", "1 2\n3 4\n");

  write("lens_spec", "circle", "circle:32,24,10");
  write("lens_spec", "circle_zoom", "circle:32,24,10:3");
  write("lens_spec", "polygon", "polygon:square");
  write("lens_spec", "polygon_zoom", "polygon:square:2.5");
  write("lens_spec", "mask", "mask:mask");
  write("lens_spec", "mask_zoom", "mask:mask:4");
  write("lens_spec", "polygon_junk", "polygon:junk");
  write("lens_spec", "short", "circle:1,2");
  write("lens_spec", "unknown", "ellipse:1,2,3");
  write("lens_spec", "huge", "circle:1e400,0,5:nan");

  write("geojson", "collection.geojson",
        R"({"type":"FeatureCollection","features":[
{"type":"Feature","id":7,"geometry":{"type":"Point","coordinates":[1.5,2]},"properties":{"name":"a"}},
{"type":"Feature","geometry":{"type":"MultiPoint","coordinates":[[1,2],[3,4]]},"properties":null},
{"type":"Feature","geometry":{"type":"LineString","coordinates":[[0,0],[10,5]]},"properties":{}},
{"type":"Feature","geometry":{"type":"MultiLineString","coordinates":[[[0,0],[1,1]],[[2,2],[3,1]]]},"properties":null},
{"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[4,4],[0,0]],[[1,1],[2,1],[2,2],[1,1]]]},"properties":null},
{"type":"Feature","geometry":{"type":"MultiPolygon","coordinates":[[[[0,0],[1,0],[1,1],[0,0]]],[[[5,5],[6,5],[6,6],[5,5]]]]},"properties":null},
{"type":"Feature","geometry":null,"properties":{"k":[1,"x",true]}}
]})");
  write(
      "geojson", "feature.geojson",
      R"({"type":"Feature","id":"f1","bbox":[0,0,1,1],"geometry":{"type":"GeometryCollection","geometries":[{"type":"Point","coordinates":[0,1]},{"type":"GeometryCollection","geometries":[]}]},"properties":{"b":2,"a":1}})");
  write("geojson", "point.geojson", R"({"type":"Point","coordinates":[3e-9,-1e300]})");
  write("geojson", "altitude.geojson", R"({"type":"Point","coordinates":[1,2,3]})");
  write("geojson", "open_ring.geojson",
        R"({"type":"Polygon","coordinates":[[[0,0],[4,0],[4,4],[0,1]]]})");
  write("geojson", "not_json.geojson", "{\"type\": \"Feature\", ");

  write("map_style", "europe_style.json",
        read(fs::path(GEOLENS_SOURCE_DIR) / "examples" / "europe_style.json"));
  write(
      "map_style", "small.json",
      R"({"background":"#abc","projection":"plate_carree","layers":[{"name":"all","geometry":"polygon","fill":"#11223344","where":{"k":[1,"a",true]},"min_zoom":1,"max_zoom":4}]})");
  write("map_style", "bad_colour.json", R"({"layers":[{"fill":"#12"}]})");
  write("map_style", "unknown_key.json", R"({"extent":[10,0,5,1],"colour":"#fff"})");

  write("point_csv", "header.csv", "x,y,name\n1,2,a\n3.5, 4 ,b,c\n\n-1e-5,6e10\n");
  write("point_csv", "plain_crlf.csv", "0,0\r\n1,1,\r\n");
  write("point_csv", "bad_row.csv", "x,y\n1,2\nthree,4\n");
  write("point_csv", "single_field.csv", "5\n");

  write("obj", "tetrahedron.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write("obj", "quad_normals.obj",
        "o quad\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 "
        "4/1/1\n");
  write("obj", "relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
  write("obj", "missing_vertex.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  write("obj", "no_face.obj", "v 0 0 0\n");

  write("ply", "ascii.ply",
        "ply\nformat ascii 1.0\ncomment tiny\nelement vertex 4\nproperty float x\nproperty float "
        "y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement "
        "face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 "
        "1\n1 1 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n3 0 2 3\n");
  {
    Bytes body;
    const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& p : v) body += Bytes(reinterpret_cast<const char*>(p), sizeof p);
    const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces)
      body += Bytes(1, '\3') + Bytes(reinterpret_cast<const char*>(f), sizeof f);
    write("ply", "binary_little.ply",
          "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty "
          "float y\nproperty float z\nelement face 4\nproperty list uchar int "
          "vertex_indices\nend_header\n" +
              body);
    Bytes swapped;
    for (const auto& p : v)
      for (float c : p) {
        uint32_t bits;
        std::memcpy(&bits, &c, 4);
        swapped += big_endian32(bits);
      }
    for (const auto& f : faces) {
      swapped += Bytes(1, '\3');
      for (int i : f) swapped += big_endian32(uint32_t(i));
    }
    write("ply", "binary_big_extra.ply",
          "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty float x\nproperty float "
          "y\nproperty float z\nelement face 4\nproperty list uchar int "
          "vertex_index\nelement edge 0\nproperty int a\nend_header\n" +
              swapped);
  }
  write("ply", "bad_corner.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
        "float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 "
        "0\n0 1 0\n3 0 1 5\n");
  write("ply", "claims_rows.ply",
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float "
        "x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int "
        "vertex_indices\nend_header\n\1\2\3");
}

void volumes() {
  write("nifti", "uint8_4x3x2.nii", nifti(4, 3, 2, 2, 8, counting(24, 10)));
  {
    Bytes data;
    for (int16_t i = -6; i < 6; ++i) data += raw_of(int16_t(i * 1000));
    write("nifti", "int16_scaled_3x2x2.nii", nifti(3, 2, 2, 4, 16, data, 0.5f, 10));
  }
  {
    Bytes data;
    for (int i = 0; i < 8; ++i) data += raw_of(float(i) * 0.25f);
    write("nifti", "float32_4d_2x2x2.nii", nifti(2, 2, 2, 16, 32, data, 0, 0, 4));
  }
  write("nifti", "short_data.nii", nifti(8, 8, 8, 2, 8, counting(20)));
  write("nifti", "zero_dim.nii", nifti(0, 3, 2, 2, 8, counting(6)));
  write("nifti", "rgb_type.nii", nifti(2, 2, 1, 128, 24, counting(12)));

  write("nrrd", "raw_uint8.nrrd",
        "NRRD0004\n# a comment\ntype: uchar\ndimension: 3\nsizes: 3 2 2\nencoding: "
        "raw\nspacings: 1 2 nan\n\n" +
            counting(12, 20));
  {
    Bytes samples;
    for (int i = 0; i < 8; ++i) samples += Bytes(1, '\0') + Bytes(1, char(i * 30));  // big endian
    write("nrrd", "gzip_int16_big.nrrd",
          "NRRD0005\ntype: short\ndimension: 3\nsizes: 2 2 2\nendian: big\nencoding: gzip\nspace "
          "directions: (1,0,0) (0,2,0) (0,0,0.5)\nkey:=value\n\n" +
              gzip(samples));
  }
  {
    Bytes samples;
    for (int i = 0; i < 8; ++i) samples += raw_of(float(i) - 3.5f);
    write("nrrd", "float_byte_skip_end.nrrd",
          "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\nbyte "
          "skip: -1\nline skip: 1\n\nignored line\n" +
              samples);
  }
  write("nrrd", "detached_self.nrrd",
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\nbyte skip: -1\ndata "
        "file: input.nrrd\n\n" +
            counting(8, 30));
  write("nrrd", "short_data.nrrd",
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n" + counting(10));
  write("nrrd", "bad_dimension.nrrd",
        "NRRD0004\ntype: uint8\ndimension: 2\nsizes: 2 2\n\n\1\2\3\4");
}

void folders() {
  write("levels", "three_levels.txt",
        "png a.png 16 12 3\npng b.png 8 6 3\npng c.png 2 2 1\nline a.png\nline b.png\nline "
        "# comment\nline   c.png  \n");
  write("levels", "rounded_jpeg.txt",
        "png fine.png 13 7 4\njpg half.jpg 7 4\nline half.jpg\nline fine.png\nsize 7 0\n");
  write("levels", "raw_header.txt",
        "raw big.png \\x89PNG\\x0d\\n\\x1a\\n\\x00\\x00\\x00\\x0dIHDR\\x00\\x00\\x00\\x40\\x00\\x00"
        "\\x00\\x20\\x08\\x02\\x00\\x00\\x00\njpg small.jpg 16 8\nline big.png\nline small.jpg\n");
  write("levels", "same_level.txt", "png a.png 8 8 1\npng b.png 8 8 1\nline a.png\nline b.png\n");
  write("levels", "aspect.txt", "png a.png 16 16 3\npng b.png 8 3 3\nline a.png\nline b.png\n");
  write("levels", "missing.txt", "line nothing.png\ndir d\nline d\n");

  write("tiles", "xyz.txt",
        "png 0/0/0.png 8 8 3\npng 1/0/0.png 8 8 3\npng 1/1/1.png 8 8 1\ndir 2\njpg 2/3/3.jpg 8 "
        "8\nsize 20\nfetch 0 0 0 32 32\nfetch 1 -3 5 20 4\nfetch 3 0 0 1 1\n");
  write("tiles", "xyz_root_only.txt", "png 0/0/0.png 4 4 4\n");
  write("tiles", "xyz_gap.txt", "png 0/0/0.png 4 4 2\ndir 2\n");
  write("tiles", "xyz_odd_root.txt", "png 0/0/0.png 5 5 3\ndir 1\n");
  write("tiles", "xyz_mixed_sizes.txt",
        "png 0/0/0.png 4 4 3\npng 1/0/1.png 8 8 3\nraw 1/1/0.png \\x89PNG\nfetch 0 0 0 8 8\n");
  write("tiles", "own_layout.txt",
        "png 0/0_0.png 4 4 3\npng 0/1_0.png 4 4 3\npng 0/0_1.png 4 2 3\npng 0/1_1.png 4 2 3\npng "
        "1/0_0.png 4 3 3\npng 2/0_0.png 2 2 3\npng 3/0_0.png 1 1 3\ntiled 8 6 3 4\n");
  write("tiles", "own_layout_wrong.txt", "png 0/0_0.png 4 4 1\ntiled 4 4 3 4\nfetch 0 0 0 4 4\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_fuzz_seeds DIR\n");
    return 2;
  }
  out_dir = argv[1];
  images();
  masks();
  text_kinds();
  volumes();
  folders();
  return 0;
}
