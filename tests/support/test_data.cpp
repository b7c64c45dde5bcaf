#include "support/test_data.h"

namespace geolens::test {

WarpMesh grid_warp(int cols, int rows, double width, double height, const ScreenOf& screen_of,
                   int screen_width, int screen_height) {
  WarpMesh mesh;
  mesh.source.resize(cols * rows, 2);
  mesh.screen.resize(cols * rows, 2);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const Eigen::Vector2d s(width * i / (cols - 1), height * j / (rows - 1));
      mesh.source.row(j * cols + i) = s;
      mesh.screen.row(j * cols + i) = screen_of(s);
    }
  mesh.F.resize(2 * (cols - 1) * (rows - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      const int a = j * cols + i, b = a + 1, c = a + cols, d = c + 1;
      if ((i + j) % 2 == 0) {
        mesh.F.row(f++) << a, b, d;
        mesh.F.row(f++) << a, d, c;
      } else {
        mesh.F.row(f++) << a, b, c;
        mesh.F.row(f++) << b, d, c;
      }
    }
  mesh.screen_width = screen_width;
  mesh.screen_height = screen_height;
  return mesh;
}

Image pattern(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int ch = 0; ch < channels; ++ch)
        image.at(x, y)[ch] = uint8_t((x * 7 + y * 13 + ch * 101 + x * y) % 256);
  return image;
}

Image crop(const Image& image, int x, int y, int width, int height) {
  Image out(width, height, image.channels);
  for (int j = 0; j < height; ++j)
    std::copy(image.at(x, y + j), image.at(x + width, y + j), out.at(0, j));
  return out;
}

WarpMesh magnified_patch(int side, const Eigen::Vector2d& source_min, double source_side,
                         const Eigen::Vector2d& screen_min, double screen_side) {
  const WarpMesh identity = identity_warp(side, side);
  WarpMesh mesh = identity;
  mesh.F.conservativeResize(4, 3);
  mesh.F.bottomRows(2) = identity.F.array() + 4;
  mesh.source.conservativeResize(8, 2);
  mesh.screen.conservativeResize(8, 2);
  mesh.source.bottomRows(4) =
      (identity.source * (source_side / side)).rowwise() + source_min.transpose();
  mesh.screen.bottomRows(4) =
      (identity.source * (screen_side / side)).rowwise() + screen_min.transpose();
  return mesh;
}

}  // namespace geolens::test
