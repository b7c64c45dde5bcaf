#include "geolens/core/parse.h"

#include <gtest/gtest.h>

#include <string>

#include "geolens/core/errors.h"
#include "support/refusal.h"

namespace geolens {
namespace {

TEST(Parse, ANumberIsTheWholeTextAndFinite) {
  for (const auto& [text, value] : {std::pair{"2", 2.0},
                                    {"0.25", 0.25},
                                    {"1e-3", 1e-3},
                                    {"-4", -4.0},
                                    {"+3.5", 3.5},
                                    {".5", 0.5}}) {
    ASSERT_TRUE(read_number(text).has_value()) << text;
    EXPECT_EQ(*read_number(text), value) << text;
  }
  for (const char* text : {"", " 2", "2 ", "nan", "inf", "-inf", "1e999", "abc", "2x", "1,5"})
    EXPECT_FALSE(read_number(text).has_value()) << "'" << text << "'";
}

TEST(Parse, AnIntegerIsDigitsWithinIntsRange) {
  EXPECT_EQ(read_integer("100"), 100);
  EXPECT_EQ(read_integer("-1"), -1);
  EXPECT_EQ(read_integer("2147483647"), 2147483647);
  for (const char* text : {"", "1e3", "2.0", "2147483648", "-2147483649", "99999999999999999999",
                           " 5", "5 ", "0x10", "ten"})
    EXPECT_FALSE(read_integer(text).has_value()) << "'" << text << "'";
}

TEST(Parse, AFailureNamesWhatWasReadAndQuotesTheText) {
  try {
    parse_integer("2.5", "--mesh");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "--mesh: must be an integer, got '2.5'");
  }
  try {
    parse_number("fast", "set heat_max");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "set heat_max: must be a number, got 'fast'");
  }
  EXPECT_EQ(parse_number("0.5", "x"), 0.5);
}

TEST(Parse, ACountIsAWholeNumberWithinTheRange) {
  EXPECT_EQ(parse_count("268435456", "--max-pixels", 1, uint64_t(1) << 40), 268435456u);
  EXPECT_EQ(parse_count("1e9", "--max-pixels", 1, uint64_t(1) << 40), 1000000000u);
  EXPECT_EQ(parse_count("1099511627776", "--max-pixels", 1, uint64_t(1) << 40), uint64_t(1) << 40);
  const std::pair<const char*, const char*> refused[] = {
      {"0", "--max-points: must be a whole number in [1, 1024], got '0'"},
      {"-3", "--max-points: must be a whole number in [1, 1024], got '-3'"},
      {"2.5", "--max-points: must be a whole number in [1, 1024], got '2.5'"},
      {"1025", "--max-points: must be a whole number in [1, 1024], got '1025'"},
      {"nan", "--max-points: must be a number, got 'nan'"},
      {"lots", "--max-points: must be a number, got 'lots'"}};
  for (const auto& [text, message] : refused)
    EXPECT_EQ(test::refusal([&] { parse_count(text, "--max-points", 1, 1024); }), message) << text;
}

TEST(Parse, ASizeIsTwoIntegersWithinTheRange) {
  EXPECT_EQ(parse_size("640x480", "--size", 1, 16384), std::pair(640, 480));
  EXPECT_EQ(parse_size("1x16384", "--size", 1, 16384), std::pair(1, 16384));
  const std::pair<const char*, const char*> refused[] = {
      {"100", "--size: must be WxH, got '100'"},
      {"axb", "--size width: must be an integer, got 'a'"},
      {"100x", "--size height: must be an integer, got ''"},
      {"0x5", "--size: sides must be in [1, 16384], got '0x5'"},
      {"5x16385", "--size: sides must be in [1, 16384], got '5x16385'"},
      {"-5x5", "--size: sides must be in [1, 16384], got '-5x5'"}};
  for (const auto& [text, message] : refused)
    EXPECT_EQ(test::refusal([&] { parse_size(text, "--size", 1, 16384); }), message) << text;
}

}  // namespace
}  // namespace geolens
