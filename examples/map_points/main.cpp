// Map points both ways through a lens, with the lens engine alone (geolens::lens): where points
// of the picture land on the screen (forward), which picture point a click shows (inverse), and
// the round trip's error. Points off the warp's covered area come back empty.

#include <cstdio>
#include <exception>
#include <optional>

#include "geolens/lens/geometric_lens.h"
#include "geolens/warp/warp_map.h"

int main() {
  try {
    const geolens::GeometricLens solver(800, 600);
    const geolens::Lens lens{geolens::Region::circle({400, 300}, 50), /*zoom=*/2.5};
    const geolens::WarpMap map(solver.solve({lens}).warp);
    const Eigen::Vector2d points[] = {{400, 300}, {430, 300}, {400, 250}, {500, 300}, {700, 550}};
    for (const Eigen::Vector2d& p : points) {
      const std::optional<Eigen::Vector2d> screen = map.forward(p);
      if (!screen) continue;
      const std::optional<Eigen::Vector2d> back = map.inverse(*screen);
      std::printf("picture (%5.1f, %5.1f) -> screen (%6.2f, %6.2f) -> picture, off by %.1e px\n",
                  p.x(), p.y(), screen->x(), screen->y(), back ? (*back - p).norm() : -1.0);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "map_points: %s\n", e.what());
    return 1;
  }
}
