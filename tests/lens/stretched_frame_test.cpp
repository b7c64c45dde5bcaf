// Thin regions solved in a stretched frame (lens/stretched_frame.h): a line of text in a page gets
// the zoom asked where its magnified focus has the room, continuously as it is dragged and as its
// shape changes, with its focus still exact and nothing beyond its footprint moved.

#include "lens/stretched_frame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "geolens/eval/comparison.h"
#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens_session.h"
#include "geolens/measure/distortion.h"

namespace geolens {
namespace {

Lens box(double x0, double y0, double x1, double y1, double zoom) {
  return Lens{Region::polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}), zoom};
}

// A phrase of a line of text (make_figure_inputs's page) as a mask's blob, 238 x 20 px (its
// traced outline); with `hole`, a hole in it (then no outline).
Lens masked_phrase(double zoom, bool hole = false) {
  Image mask(1024, 1024, 1);
  for (int y = 300; y < 320; ++y)
    for (int x = 362; x < 600; ++x)
      mask.at(x, y)[0] = hole && y > 305 && y < 314 && x > 400 && x < 420 ? 0 : 255;
  return Lens{Region::from_mask(mask).front(), zoom};
}

TEST(FrameStretch, GrowsContinuouslyWithTheAspectAndACircleKeepsTheFrame) {
  EXPECT_EQ(frame_stretch({}), Eigen::Vector2d::Ones());
  double last = 1;
  for (double width = 40; width <= 480; width += 1) {
    const Eigen::Vector2d s = frame_stretch({box(10, 10, 10 + width, 50, 2)});
    EXPECT_EQ(s.x(), 1) << width;  // wider than tall: stretched across, along y
    EXPECT_GE(s.y(), last) << width;
    EXPECT_LE(s.y() - last, 0.01) << width;
    if (width <= kStretchFrom * 40) EXPECT_EQ(s.y(), 1) << width;
    if (width >= kStretchFull * 40) EXPECT_EQ(s.y(), kMostStretch) << width;
    last = s.y();
  }
  EXPECT_EQ(frame_stretch({box(10, 10, 50, 410, 2)}), Eigen::Vector2d(kMostStretch, 1));
  // The least of the lenses' along each axis: a tall and a wide one, or a circle, keep the frame.
  EXPECT_EQ(frame_stretch({box(10, 10, 50, 410, 2), box(100, 10, 500, 50, 2)}),
            Eigen::Vector2d::Ones());
  EXPECT_EQ(frame_stretch({box(100, 10, 500, 50, 2), Lens{Region::circle({300, 300}, 40), 2}}),
            Eigen::Vector2d::Ones());
  // A mask's blob by its outline; one with a hole has none.
  EXPECT_EQ(frame_stretch({masked_phrase(2)}), Eigen::Vector2d(1, kMostStretch));
  EXPECT_EQ(frame_stretch({masked_phrase(2, true)}), Eigen::Vector2d::Ones());
}

// The line of text with its heading on make_figure_inputs's page (examples/text_line_polygon.txt,
// 266 x 20 px, 226 px below the top side) gets 2.8 of the zoom 3 asked and a phrase of a line
// below it (238 x 20), as a polygon or as a mask, gets 3 (1.83, 2.48 and 2.48 in the image's
// frame, held by the top side: a ring about a point has, above a thin line, the line's own extent
// along it), magnified exactly as a whole, nothing flipped and nothing beyond the footprint moved.
TEST(StretchedFrame, ALineOfTextInAPageGetsItsZoom) {
  const GeometricLens page(1024, 1024);
  struct Line {
    Lens lens;
    double least;
  };
  for (const auto& [line, least] :
       {Line{box(358, 226, 624, 246, 3), 2.8}, Line{box(362, 300, 600, 320, 3), 3.0},
        Line{masked_phrase(3), 3.0}}) {
    const LensResult r = page.solve({line});
    const TriangleDistortion measures = measure_triangles(r.warp);
    const FocusMeasure focus = measure_foci(r.warp, measures, {line}).front();
    EXPECT_GE(r.zoom_fits.at(0), least);
    EXPECT_NEAR(focus.zoom / r.zoom_fits[0], 1, 1e-6);
    EXPECT_LE(focus.uniformity, 1.0001);
    EXPECT_LE(focus.shape_max, 1e-9);
    EXPECT_EQ(summarize(measures).flipped, 0);
    EXPECT_EQ(focus.displacement_beyond_footprint, 0);
    // The warp is the image's: its source is the image, its screen framed at the image's size.
    EXPECT_EQ(r.warp.screen_width, 1024);
    EXPECT_EQ(r.warp.screen_height, 1024);
    EXPECT_NEAR(r.warp.source.col(1).maxCoeff(), 1024, 1e-9);
    EXPECT_NEAR(r.warp.screen.col(1).maxCoeff(), 1024, 1e-9);
  }
}

// A reason names a distance in the image's pixels, not the frame's: a line 150 px below the top
// side (across the frame's stretch) and a tall one 300 px below it (along it), each short of 3.
TEST(StretchedFrame, AReasonNamesTheImagesPixels) {
  const GeometricLens page(1024, 1024);
  for (const auto& [line, gap] :
       {std::pair{box(362, 150, 600, 170, 3), 150}, std::pair{box(502, 300, 522, 540, 3), 300}}) {
    const LensResult r = page.solve({line});
    ASSERT_LT(r.zoom_fits.at(0), 3);
    const std::string side = "the image's top side, " + std::to_string(gap) + " px from the region";
    EXPECT_EQ(r.zoom_fit_reasons.at(0).rfind(side, 0), 0u) << r.zoom_fit_reasons[0];
  }
}

// Dragged 4 px a step in a session towards a side and onto it, a line keeps a continuous zoom
// (in the image's frame a 300 x 16 line dragged to the left side fell to 1.30 and stepped by 0.33
// in 4 px), and asked 1 to 8 in steps of 0.25 it never gets less for asking more.
TEST(StretchedFrame, ALineDraggedToASideKeepsAContinuousZoom) {
  struct Drag {
    double x0, y0, dx, dy;  // its first corner, and each step
    int steps;
    double zoom, least;
  };
  for (const Drag& d : {Drag{300, 500, -4, 0, 75, 2, 1.8}, Drag{392, 390, 0, -4, 95, 2, 2.0}}) {
    LensSession session(1024, 1024);
    std::vector<double> zooms;
    for (int k = 0; k <= d.steps; ++k) {
      const double x = std::max(0.0, d.x0 + k * d.dx), y = std::max(0.0, d.y0 + k * d.dy);
      const bool wide = d.dx != 0;
      const LensResult r = session.update(
          {wide ? box(x, y, x + 300, y + 16, d.zoom) : box(x, y, x + 240, y + 20, d.zoom)});
      EXPECT_EQ(summarize(measure_triangles(r.warp)).flipped, 0) << k;
      zooms.push_back(r.zoom_fits.at(0));
    }
    EXPECT_GE(*std::min_element(zooms.begin(), zooms.end()), d.least * (1 - 1e-9));
    for (size_t k = 1; k < zooms.size(); ++k)
      EXPECT_LE(std::abs(zooms[k] - zooms[k - 1]), 0.03) << d.x0 << " " << k;
  }
  const GeometricLens page(1024, 1024);
  double last = 1;
  for (double zoom = 1; zoom <= 8; zoom += 0.25) {
    const double got = page.solve({box(362, 300, 600, 320, zoom)}).zoom_fits.at(0);
    EXPECT_GE(got, last * (1 - 1e-9)) << zoom;
    last = got;
  }
}

// As a line grows from 3 to 10 times as wide as it is tall, through the stretch's ramp, its zoom
// changes by at most 0.05 a 4 px step.
TEST(StretchedFrame, ALineGrowingThroughTheRampKeepsAContinuousZoom) {
  const GeometricLens page(1024, 1024);
  double last = 0;
  for (double width = 120; width <= 400; width += 4) {
    const double got =
        page.solve({box(512 - width / 2, 480, 512 + width / 2, 520, 3)}).zoom_fits.at(0);
    if (last > 0) EXPECT_LE(std::abs(got - last), 0.05) << width;
    last = got;
  }
}

}  // namespace
}  // namespace geolens
