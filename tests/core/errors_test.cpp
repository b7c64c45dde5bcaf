// The texts messages are made of: numbers that read back to themselves, lines of a user's file
// shown safely, and options named apart from the problem.

#include "geolens/core/errors.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <random>
#include <string>

namespace geolens {
namespace {

TEST(NumberText, ReadsBackToTheSameDouble) {
  std::mt19937_64 random(3);
  for (int i = 0; i < 10000; ++i) {
    const double value =
        std::ldexp(double(random()) / double(random.max()) - 0.5, int(random() % 2000) - 1000);
    const std::string text = number_text(value);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), value) << text;
    EXPECT_LE(text.size(), 24u) << text;  // never 309 digits
  }
  EXPECT_EQ(number_text(1e308), "1e+308");
  EXPECT_EQ(number_text(180.00000000000014), "180.00000000000014");
  EXPECT_EQ(number_text(0.5), "0.5");
}

TEST(QuotedLine, ShowsPrintableAsciiAsIsAndEveryOtherByteAsHex) {
  EXPECT_EQ(quoted_line("10 20"), "10 20");
  EXPECT_EQ(quoted_line(std::string("a\x1b[2Jb\r\t\x7f\xc3\xa9", 11)),
            "a\\x1b[2Jb\\x0d\\x09\\x7f\\xc3\\xa9");
  std::string all;
  for (int c = 0; c < 256; ++c) all += char(c);
  for (size_t from = 0; from < all.size(); from += 50) {
    const std::string shown = quoted_line(all.substr(from, 50));
    for (const char c : shown) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << int(c);
  }
}

TEST(QuotedLine, CutsALongLineAndSaysHowLongItWas) {
  const std::string line(52000000, '7');
  EXPECT_EQ(quoted_line(line), std::string(60, '7') + "...(52000000 characters)");
  EXPECT_EQ(quoted_line(std::string(60, '7')), std::string(60, '7'));
}

TEST(InvalidOption, KeepsTheOptionAndTheProblemApart) {
  try {
    require_option(false, "validate", "mesh_tolerance", "must be at least 0.01, got 0.001");
    FAIL() << "not thrown";
  } catch (const InvalidInput& e) {  // an InvalidInput to whoever does not know it
    EXPECT_STREQ(e.what(), "validate: mesh_tolerance must be at least 0.01, got 0.001");
    const auto* option = dynamic_cast<const InvalidOption*>(&e);
    ASSERT_NE(option, nullptr);
    EXPECT_EQ(option->option, "mesh_tolerance");
    EXPECT_EQ(option->problem, "must be at least 0.01, got 0.001");
  }
  EXPECT_NO_THROW(require_option(true, "validate", "mesh", "unused"));
}

}  // namespace
}  // namespace geolens
