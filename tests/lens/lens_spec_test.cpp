#include "geolens/lens/lens_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "geolens/core/errors.h"
#include "geolens/io/image.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

using LensSpec = testing::ScratchFolderTest;

TEST_F(LensSpec, CircleWithAndWithoutZoom) {
  const std::vector<Lens> a =
      parse_lens_spec("circle:50,60,20:3", 2, Profile::kGaussian, 0, 200, 100);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].region.kind(), "circle");
  EXPECT_EQ(a[0].region.peak(), Eigen::Vector2d(50, 60));
  EXPECT_EQ(a[0].region.size(), 20);
  EXPECT_EQ(a[0].zoom, 3);
  EXPECT_EQ(parse_lens_spec("circle:50,60,20", 2.5, Profile::kGaussian, 5, 200, 100)[0].zoom, 2.5);
  EXPECT_EQ(parse_lens_spec("circle:50,60,20", 2.5, Profile::kGaussian, 5, 200, 100)[0].footprint,
            5);
  EXPECT_FALSE(lens_spec_file("circle:50,60,20").has_value());
}

TEST_F(LensSpec, PolygonAndMaskFilesAreRead) {
  const std::string polygon = path("p.txt");
  std::ofstream(polygon) << "10 10\n90 10\n90 50\n10 50\n";
  const std::vector<Lens> p =
      parse_lens_spec("polygon:" + polygon + ":2", 2, Profile::kGaussian, 0, 200, 100);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].region.kind(), "polygon");
  EXPECT_EQ(lens_spec_file("polygon:" + polygon + ":2")->path, polygon);
  // Two blobs, one lens each.
  Image mask(200, 100, 1);
  for (int y = 10; y < 30; ++y)
    for (int x = 10; x < 30; ++x) mask.at(x, y)[0] = mask.at(x + 100, y + 50)[0] = 1;
  save_image(path("m.png"), mask);
  EXPECT_EQ(parse_lens_spec("mask:" + path("m.png"), 2, Profile::kGaussian, 0, 200, 100).size(),
            2u);
  EXPECT_EQ(lens_spec_file("mask:" + path("m.png"))->kind, "mask");
  // Speckle (blobs under 4 pixels) is left out, said once; a mask of nothing but speckle is
  // refused.
  for (int k = 0; k < 50; ++k) mask.at(40 + 2 * k, 90 + (k % 3))[0] = 1;
  save_image(path("speckled.png"), mask);
  std::vector<std::string> warnings;
  EXPECT_EQ(
      parse_lens_spec("mask:" + path("speckled.png"), 2, Profile::kGaussian, 0, 200, 100, &warnings)
          .size(),
      2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("50 blobs of fewer than 4 pixels left out (speckle); 2 lenses kept"),
            std::string::npos)
      << warnings[0];
  Image specks(200, 100, 1);
  for (int k = 0; k < 50; ++k) specks.at(4 * k % 200, 2 * k % 100)[0] = 1;
  save_image(path("specks.png"), specks);
  EXPECT_THROW(parse_lens_spec("mask:" + path("specks.png"), 2, Profile::kGaussian, 0, 200, 100),
               InvalidInput);
  // A circle written as 10 000 vertices (0.09 px apart) is simplified to what a picture shows.
  {
    std::ofstream round(path("round.txt"));
    for (int k = 0; k < 10000; ++k)
      round << 100 + 40 * std::cos(2 * std::numbers::pi * k / 10000) << " "
            << 50 + 40 * std::sin(2 * std::numbers::pi * k / 10000) << "\n";
  }
  const std::vector<Lens> round =
      parse_lens_spec("polygon:" + path("round.txt"), 2, Profile::kGaussian, 0, 200, 100);
  ASSERT_EQ(round.size(), 1u);
  const size_t kept = round[0].region.outline()->size();
  EXPECT_GT(kept, 20u);
  EXPECT_LT(kept, 100u);
}

TEST_F(LensSpec, BadSpecsNameWhatIsWrong) {
  auto message = [](const std::string& spec) {
    try {
      parse_lens_spec(spec, 2, Profile::kGaussian, 0, 200, 100);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("square:1,2,3").find("expected circle:CX,CY,R"), std::string::npos);
  EXPECT_NE(message("circle:1,2").find("expected"), std::string::npos);
  EXPECT_NE(message("circle:50,50,0").find("radius"), std::string::npos);
  EXPECT_NE(message("circle:50,x,10").find("centre y 'x'"), std::string::npos);
  EXPECT_NE(message("circle:50,50,10:big").find("zoom 'big'"), std::string::npos);
  EXPECT_NE(message("circle:500,50,10").find("outside"), std::string::npos);
  EXPECT_NE(message("polygon:" + path("missing.txt")).find("missing.txt"), std::string::npos);
}

}  // namespace
}  // namespace geolens
