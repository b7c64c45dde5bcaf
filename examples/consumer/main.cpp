// A program that uses geolens as an installed package (scripts/package_check.sh builds it with
// find_package and with pkg-config): one focus lens on a synthetic checkerboard, solved and
// rendered; prints the zoom it measured and a checksum of the rendered pixels.

#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/render/render.h"

int main() {
  try {
    const int side = 256;
    geolens::Image source(side, side, 3);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        uint8_t* p = source.at(x, y);
        p[0] = ((x / 16 + y / 16) % 2) ? 230 : 30;
        p[1] = uint8_t(x);
        p[2] = uint8_t(y);
      }

    const geolens::GeometricLens lens(side, side);
    const std::vector<geolens::Lens> lenses = {
        {geolens::Region::circle({128, 128}, 24), /*zoom=*/2.0}};
    const geolens::LensResult result = lens.solve(lenses);

    geolens::RenderOptions options;
    options.width = side;
    options.height = side;
    const geolens::Image output =
        geolens::render(result.warp, geolens::MipPyramid(source), options);

    uint64_t checksum = 1469598103934665603ull;  // FNV-1a
    for (uint8_t byte : output.pixels) checksum = (checksum ^ byte) * 1099511628211ull;
    std::printf("zoom requested 2.00, measured %.2f; %d triangles; checksum %016llx\n",
                result.zoom_measured.at(0), int(result.warp.F.rows()),
                static_cast<unsigned long long>(checksum));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
