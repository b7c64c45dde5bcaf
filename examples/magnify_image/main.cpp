// Magnify an image: one circle at zoom 3 on a picture file, solved by the geometric lens and
// rendered at the picture's size. Usage: magnify_image INPUT OUTPUT [CX CY R]
// (default: the demo map's round plaza, examples/demo.png 512 512 60).

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "geolens/geolens.h"

int main(int argc, char** argv) {
  if (argc != 3 && argc != 6) {
    std::fprintf(stderr, "usage: magnify_image INPUT OUTPUT [CX CY R]\n");
    return 2;
  }
  try {
    const geolens::Image picture = geolens::load_image(argv[1]);
    const bool given = argc == 6;
    const geolens::Lens lens{geolens::Region::circle({given ? std::atof(argv[3]) : 512,
                                                      given ? std::atof(argv[4]) : 512},
                                                     given ? std::atof(argv[5]) : 60),
                             /*zoom=*/3.0};
    const geolens::GeometricLens solver(picture.width, picture.height);
    const geolens::LensResult result = solver.solve({lens});
    const geolens::Image output =
        geolens::render(result.warp, geolens::MipPyramid(picture),
                        {.width = picture.width, .height = picture.height});
    geolens::save_image(argv[2], output);
    std::printf("zoom asked 3, got %.3f; %d triangles, %d iterations\n", result.zoom_measured[0],
                int(result.warp.F.rows()), result.flattening.iterations);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "magnify_image: %s\n", e.what());
    return 1;
  }
}
