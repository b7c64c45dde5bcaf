#include "geolens/lens/lens_method.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/measure/distortion.h"

namespace geolens {
namespace {

// The same lens list through the one call of every method: each answers with a warp over the
// source, its zoom measured at the lens's centre as asked, and nothing folded.
TEST(LensMethod, EveryMethodMagnifiesTheSameLensesThroughOneCall) {
  const std::vector<Lens> lenses = {Lens{Region::circle({400, 380}, 60), 2.0},
                                    Lens{Region::circle({820, 700}, 40), 3.0}};
  const auto methods = every_method();
  ASSERT_EQ(methods.size(), 1 + kClassicLenses.size());
  EXPECT_EQ(methods[0]->name(), "geometric");
  for (const auto& method : methods) {
    SCOPED_TRACE(method->name());
    const Magnification m = method->magnify(lenses, 1024, 1024);
    EXPECT_EQ(m.warp.screen_width, 1024);
    EXPECT_EQ(m.warp.screen_height, 1024);
    ASSERT_EQ(m.zoom_measured.size(), lenses.size());
    ASSERT_EQ(m.zoom_parameter.size(), lenses.size());
    for (size_t k = 0; k < lenses.size(); ++k)
      EXPECT_NEAR(m.zoom_measured[k] / lenses[k].zoom, 1.0, 0.05) << "lens " << k;
    EXPECT_EQ(summarize(measure_triangles(m.warp)).flipped, 0);
  }
}

// A classic lens reads a Lens as the focus model does: the region is shown at the lens's zoom
// by the flat top, uniformly.
TEST(LensMethod, AClassicFlatTopShowsTheRegionAtItsZoom) {
  const Lens lens{Region::circle({500, 520}, 70), 2.5};
  for (ClassicLens kind : {ClassicLens::kBifocal, ClassicLens::kFlattopLinear,
                           ClassicLens::kFlattopCosine, ClassicLens::kPowerRing}) {
    SCOPED_TRACE(to_string(kind));
    const Magnification m = ClassicMethod(kind).magnify({lens}, 1024, 1024);
    const FocusMeasure f = measure_foci(m.warp, measure_triangles(m.warp), {lens}).front();
    EXPECT_NEAR(f.zoom, 2.5, 0.05);
    EXPECT_LT(f.uniformity, 1.02);
  }
  const CircleLens c = ClassicMethod::circle_lens(lens);
  EXPECT_EQ(c.radius, 2 * 2.5 * 70);  // the default footprint: 2 x zoom
  EXPECT_EQ(c.focus_fraction, 0.5);
}

TEST(LensMethod, CircleLensAndLensForAreInverse) {
  const CircleLens c{{300, 200}, 180, 2.2, 0.4};
  const CircleLens back = ClassicMethod::circle_lens(ClassicMethod::lens_for(c));
  EXPECT_EQ(back.center, c.center);
  EXPECT_NEAR(back.radius, c.radius, 1e-12 * c.radius);
  EXPECT_EQ(back.zoom, c.zoom);
  EXPECT_NEAR(back.focus_fraction, c.focus_fraction, 1e-15);
  EXPECT_THROW(ClassicMethod::lens_for({{300, 200}, 180, 2.2, 0.97}), InvalidInput);
}

TEST(LensMethod, AClassicLensNeedsACircle) {
  const Lens square{Region::polygon({{400, 400}, {500, 400}, {500, 500}, {400, 500}}), 2.0};
  try {
    ClassicMethod(ClassicLens::kFisheye).magnify({square}, 1024, 1024);
    FAIL() << "a polygon was taken";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("circle"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ClassicMethod(ClassicLens::kFisheye, {3, {}}), InvalidInput);
  EXPECT_THROW(ClassicMethod(ClassicLens::kFisheye, {200, {5.0, 5.0}})
                   .magnify({Lens{Region::circle({500, 500}, 50), 2.0}}, 1024, 1024),
               InvalidInput);
}

// The geometric method's zoom parameter is the zoom each lens was solved at: the largest that
// fits for a lens that asks for more than fits where it is.
TEST(LensMethod, TheGeometricZoomParameterIsTheZoomSolvedAt) {
  const Lens fits{Region::circle({512, 512}, 60), 2.0};
  const Lens cornered{Region::circle({60, 60}, 50), 6.0};
  const Magnification m = GeometricMethod().magnify({fits, cornered}, 1024, 1024);
  EXPECT_EQ(m.zoom_parameter[0], 2.0);
  EXPECT_LT(m.zoom_parameter[1], 6.0);
  EXPECT_NEAR(m.zoom_measured[1] / m.zoom_parameter[1], 1.0, 0.05);
}

}  // namespace
}  // namespace geolens
