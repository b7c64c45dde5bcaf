#include "geolens/core/errors.h"

#include <charconv>

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

std::string number_text(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

}  // namespace geolens
