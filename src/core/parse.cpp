#include "geolens/core/parse.h"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

// strtod and strtol skip leading spaces; a value written by a user must not start with one.
bool starts_with_space(const std::string& text) {
  return !text.empty() && std::isspace(static_cast<unsigned char>(text[0]));
}

}  // namespace

std::optional<double> read_number(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || starts_with_space(text) || end != text.c_str() + text.size() ||
      !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<int> read_integer(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || starts_with_space(text) || end != text.c_str() + text.size() ||
      errno == ERANGE || value < INT_MIN || value > INT_MAX)
    return std::nullopt;
  return int(value);
}

double parse_number(const std::string& text, const std::string& what) {
  const std::optional<double> value = read_number(text);
  require(value.has_value(), what.c_str(), "must be a number, got '" + text + "'");
  return *value;
}

int parse_integer(const std::string& text, const std::string& what) {
  const std::optional<int> value = read_integer(text);
  require(value.has_value(), what.c_str(), "must be an integer, got '" + text + "'");
  return *value;
}

uint64_t parse_count(const std::string& text, const std::string& what, uint64_t lo, uint64_t hi) {
  const double value = parse_number(text, what);
  require(value >= double(lo) && value <= double(hi) && value == std::floor(value), what.c_str(),
          "must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
              "], got '" + text + "'");
  return uint64_t(value);
}

std::pair<int, int> parse_size(const std::string& text, const std::string& what, int lo, int hi) {
  const size_t x = text.find('x');
  require(x != std::string::npos, what.c_str(), "must be WxH, got '" + text + "'");
  const int width = parse_integer(text.substr(0, x), what + " width");
  const int height = parse_integer(text.substr(x + 1), what + " height");
  require(width >= lo && width <= hi && height >= lo && height <= hi, what.c_str(),
          "sides must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" +
              text + "'");
  return {width, height};
}

}  // namespace geolens
