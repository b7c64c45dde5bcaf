// A lens dragged in a GUI's loop, with the lens engine alone (geolens::lens; built by
// scripts/package_check.sh with find_package and with pkg-config): a circle of zoom 3 dragged
// across a 640 x 400 picture, one LensSession update a frame (a draft while it moves, a full
// frame where it rests), then a click on the magnified focus picked back to the picture.

#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>

#include "geolens/lens/lens_session.h"
#include "geolens/warp/warp_map.h"

int main() {
  try {
    geolens::LensSession session(640, 400);
    geolens::LensResult frame;
    for (int step = 0; step <= 8; ++step) {
      const geolens::Lens lens{geolens::Region::circle({120.0 + 50 * step, 200}, 30), 3.0};
      frame = session.update({lens}, {}, /*draft=*/step < 8);
      std::printf("frame %d: lens at x %d, zoom %.2f%s\n", step, 120 + 50 * step,
                  frame.zoom_measured.at(0), step < 8 ? " (draft)" : "");
    }
    const geolens::WarpMap map(frame.warp);
    const std::optional<Eigen::Vector2d> picked = map.inverse({530, 215});
    if (!picked) throw std::runtime_error("the click is on no triangle");
    std::printf("a click at (530, 215) is the picture's (%.1f, %.1f)\n", picked->x(), picked->y());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "drag_session: %s\n", e.what());
    return 1;
  }
}
