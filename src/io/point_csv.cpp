#include "geolens/io/point_csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

namespace {

/// 2^22 points of a few columns; a larger file is refused before it is read.
constexpr size_t kMaxCsvBytes = size_t(256) << 20;

// The fields of a line cut at its first two commas: x, y and the rest from the second comma on
// (each of x and y empty when missing).
struct Fields {
  std::string_view x, y, rest;
  bool has_y = false;
};

Fields split(std::string_view line) {
  Fields f;
  const size_t first = line.find(',');
  f.x = line.substr(0, first);
  if (first == std::string_view::npos) return f;
  f.has_y = true;
  const size_t second = line.find(',', first + 1);
  f.y = line.substr(first + 1, second == std::string_view::npos ? second : second - first - 1);
  if (second != std::string_view::npos) f.rest = line.substr(second);
  return f;
}

// The field as a finite number, spaces around it allowed.
std::optional<double> number(std::string_view field) {
  const size_t begin = field.find_first_not_of(" \t");
  if (begin == std::string_view::npos) return std::nullopt;
  field = field.substr(begin, field.find_last_not_of(" \t") - begin + 1);
  double v = 0;
  const auto [end, status] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (status != std::errc() || end != field.data() + field.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

void append_number(std::string& text, double v) {
  char buffer[32];
  const auto [end, status] = std::to_chars(buffer, buffer + sizeof buffer, v);
  text.append(buffer, end);
}

}  // namespace

PointTable parse_point_csv(const std::string& text, const std::string& name, size_t max_points) {
  PointTable table;
  std::vector<double> coordinates;
  std::string_view rest = text;
  bool first = true;  // the first line that is not blank: perhaps the header
  for (size_t number_of_line = 1; !rest.empty(); ++number_of_line) {
    const size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    // Every carriage return that ends the line: "\r\r\n" left one in a header or a line's rest,
    // and the text written back, its line ending "\n", read back without it.
    while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    const Fields f = split(line);
    const std::optional<double> x = number(f.x), y = number(f.y);
    if (first && !x && !y) {
      table.header = line;
      first = false;
      continue;
    }
    first = false;
    require(x && y && f.has_y, "parse_point_csv",
            name + ":" + std::to_string(number_of_line) +
                ": expected two finite numbers \"x,y\" first, got \"" + quoted_line(line) + "\"");
    require(table.rest.size() < max_points, "parse_point_csv",
            name + ":" + std::to_string(number_of_line) + ": more than the " +
                std::to_string(max_points) +
                " points read (max_points; --max-points raises it, or split the file)");
    coordinates.push_back(*x);
    coordinates.push_back(*y);
    table.rest.emplace_back(f.rest);
  }
  table.points = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(
      coordinates.data(), Eigen::Index(coordinates.size() / 2), 2);
  return table;
}

PointTable read_point_csv(const std::string& path, size_t max_points) {
  const size_t bytes = std::max(kMaxCsvBytes, std::min(max_points, size_t(1) << 40) * 64);
  return parse_point_csv(read_file(path, "read_point_csv", "CSV", bytes), path, max_points);
}

std::string point_csv_text(const PointTable& table) {
  require(table.rest.size() == size_t(table.points.rows()), "point_csv_text",
          "rest has " + std::to_string(table.rest.size()) + " rows for " +
              std::to_string(table.points.rows()) + " points");
  std::string text;
  if (!table.header.empty()) text += table.header + "\n";
  for (Eigen::Index i = 0; i < table.points.rows(); ++i) {
    require(table.points.row(i).allFinite(), "point_csv_text",
            "point " + std::to_string(i) + " is not finite");
    append_number(text, table.points(i, 0));
    text += ',';
    append_number(text, table.points(i, 1));
    text += table.rest[size_t(i)];
    text += '\n';
  }
  return text;
}

}  // namespace geolens
