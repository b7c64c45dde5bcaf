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

}  // namespace geolens::test
