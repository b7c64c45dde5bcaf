#include <gtest/gtest.h>

#include "geolens/core/errors.h"
#include "geolens/lens/lens.h"

namespace geolens {
namespace {

class ProfileTest : public ::testing::TestWithParam<Profile> {};

TEST_P(ProfileTest, ZeroAtTheRimOneAtTheCentreMonotoneBetween) {
  const Profile p = GetParam();
  EXPECT_NEAR(profile_value(p, 0), 0, 1e-12);
  EXPECT_NEAR(profile_value(p, 1), 1, 1e-12);
  EXPECT_EQ(profile_value(p, -0.5), 0);
  double previous = 0;
  for (int i = 1; i <= 100; ++i) {
    const double v = profile_value(p, i / 100.0);
    EXPECT_GE(v, previous - 1e-15);
    previous = v;
  }
}

INSTANTIATE_TEST_SUITE_P(All, ProfileTest,
                         ::testing::Values(Profile::kGaussian, Profile::kSphere, Profile::kMesa));

TEST(Profile, MesaIsFlatOnTop) {
  EXPECT_DOUBLE_EQ(profile_value(Profile::kMesa, 0.5), 1);
  EXPECT_DOUBLE_EQ(profile_value(Profile::kMesa, 0.75), 1);
}

TEST(Profile, ParsesNamesAndRejectsOthers) {
  for (Profile p : {Profile::kGaussian, Profile::kSphere, Profile::kMesa})
    EXPECT_EQ(parse_profile(to_string(p)), p);
  EXPECT_THROW(parse_profile("cone"), InvalidInput);
}

}  // namespace
}  // namespace geolens
