// The geometric lens beside a classic lens: the same circle at zoom 3 magnified by the focus
// lens and by each classic lens matched to it (LensMethod), with what each costs the context:
// the zoom measured at the focus and the largest and mean shape distortion of the warp.

#include <cstdio>
#include <exception>
#include <memory>

#include "geolens/lens/lens_method.h"
#include "geolens/measure/distortion.h"

int main() {
  try {
    const std::vector<geolens::Lens> lenses = {
        {geolens::Region::circle({320, 240}, 40), /*zoom=*/3.0}};
    std::printf("%-16s %6s %10s %10s\n", "method", "zoom", "shape max", "shape mean");
    for (const std::unique_ptr<geolens::LensMethod>& method : geolens::every_method()) {
      const geolens::Magnification m = method->magnify(lenses, 640, 480);
      const geolens::DistortionSummary shape =
          geolens::summarize(geolens::measure_triangles(m.warp));
      std::printf("%-16s %6.3f %10.3f %10.4f\n", method->name().c_str(), m.zoom_measured[0],
                  shape.conformal_max, shape.conformal_mean);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "classic_compare: %s\n", e.what());
    return 1;
  }
}
