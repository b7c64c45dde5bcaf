#include "geolens/core/errors.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <version>

namespace geolens {

void require(bool condition, const char* function, const std::string& what) {
  if (!condition) throw InvalidInput(std::string(function) + ": " + what);
}

InvalidOption::InvalidOption(const char* function, const std::string& option,
                             const std::string& problem)
    : InvalidInput(std::string(function) + ": " + option + " " + problem),
      option(option),
      problem(problem) {}

void require_option(bool condition, const char* function, const std::string& option,
                    const std::string& problem) {
  if (!condition) throw InvalidOption(function, option, problem);
}

std::string quoted_line(std::string_view line) {
  constexpr size_t kShown = 60;
  std::string text;
  for (const char c : line.substr(0, kShown)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      text += c;
    } else {
      constexpr const char* kHex = "0123456789abcdef";
      text += {'\\', 'x', kHex[byte >> 4], kHex[byte & 15]};
    }
  }
  if (line.size() > kShown) text += "...(" + std::to_string(line.size()) + " characters)";
  return text;
}

#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
std::string number_text(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}
#else
namespace {

// `digits` (decimal, no sign) plus `step` (+1 or -1) in its last digit; `exponent` follows a carry
// out of the first digit or a borrow that leaves it 0. Empty when the result would be 0.
std::string step_digits(std::string digits, int& exponent, int step) {
  size_t i = digits.size();
  while (i-- > 0) {
    if (step > 0 && digits[i] == '9') {
      digits[i] = '0';
      continue;
    }
    if (step < 0 && digits[i] == '0') {
      digits[i] = '9';
      continue;
    }
    digits[i] = char(digits[i] + step);
    break;
  }
  if (i == size_t(-1)) {  // 99 + 1: carry out of the first digit
    digits.insert(digits.begin(), '1');
    digits.pop_back();
    ++exponent;
  } else if (digits[0] == '0') {  // 10 - 1 = 09
    digits.erase(digits.begin());
    if (digits.empty()) return digits;
    --exponent;
  }
  return digits;
}

std::string scientific_text(bool negative, const std::string& digits, int exponent) {
  std::string text = negative ? "-" : "";
  text += digits[0];
  if (digits.size() > 1) text += "." + digits.substr(1);
  char tail[16];
  std::snprintf(tail, sizeof tail, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
  return text + tail;
}

}  // namespace

// A C++ library without std::to_chars for double (emscripten 3.1.6's libc++ 14): the same text
// as std::to_chars(first, last, value). The fewest digits that read back (printf's correctly
// rounded %.*e, or the next digits up or down where that one does not read back), written fixed
// or scientific, whichever is shorter (fixed on a tie; an integer with all its digits, as
// printf's %.0f).
std::string number_text(double value) {
  char text[40];
  if (!std::isfinite(value))
    return std::string(text, size_t(std::snprintf(text, sizeof text, "%g", value)));
  const bool negative = std::signbit(value);
  std::string digits, scientific;
  int exponent = 0;
  for (int precision = 0; precision < 17 && scientific.empty(); ++precision) {
    std::snprintf(text, sizeof text, "%.*e", precision, std::fabs(value));  // D[.DDD]e(+|-)XX
    const char* e = std::strchr(text, 'e');
    const int rounded_exponent = std::atoi(e + 1);
    std::string rounded;
    for (const char* c = text; c < e; ++c)
      if (*c != '.') rounded += *c;
    for (const int step : {0, 1, -1}) {
      exponent = rounded_exponent;
      digits = step == 0 ? rounded : step_digits(rounded, exponent, step);
      if (digits.empty()) continue;
      const std::string candidate = scientific_text(negative, digits, exponent);
      if (std::strtod(candidate.c_str(), nullptr) == value) {
        scientific = candidate;
        break;
      }
    }
  }
  if (scientific.empty()) {  // not reached: 17 significant digits always read back
    std::snprintf(text, sizeof text, "%.16e", value);
    return text;
  }
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
  scientific = scientific_text(negative, digits, exponent);
  const int n = int(digits.size());
  std::string fixed;
  if (exponent >= n - 1) {  // an integer: its digits, exact, where that is not longer
    if (size_t(negative) + size_t(exponent) + 1 > scientific.size()) return scientific;
    fixed = std::string(text, size_t(std::snprintf(text, sizeof text, "%.0f", std::fabs(value))));
  } else if (exponent >= 0) {
    fixed = digits.substr(0, size_t(exponent + 1)) + "." + digits.substr(size_t(exponent + 1));
  } else {
    fixed = "0." + std::string(size_t(-exponent - 1), '0') + digits;
  }
  if (negative) fixed = "-" + fixed;
  return fixed.size() <= scientific.size() ? fixed : scientific;
}
#endif

}  // namespace geolens
