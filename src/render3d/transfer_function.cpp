#include "render3d/transfer_function.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

TransferFunction::TransferFunction(std::vector<TransferPoint> points) : points_(std::move(points)) {
  const char* f = "TransferFunction";
  require(!points_.empty(), f, "no control point");
  for (size_t i = 0; i < points_.size(); ++i) {
    const TransferPoint& p = points_[i];
    require(std::isfinite(p.value) && (i == 0 || p.value > points_[i - 1].value), f,
            "point " + std::to_string(i) + ": the values must be finite and increasing");
    bool in_range = p.opacity >= 0 && p.opacity <= 1;
    for (const double c : p.colour) in_range = in_range && c >= 0 && c <= 1;
    require(in_range, f, "point " + std::to_string(i) + ": colour or opacity outside [0, 1]");
  }
}

std::array<double, 4> TransferFunction::operator()(double value) const {
  auto rgba = [](const TransferPoint& p) {
    return std::array<double, 4>{p.colour[0], p.colour[1], p.colour[2], p.opacity};
  };
  if (!(value > points_.front().value)) return rgba(points_.front());
  if (value >= points_.back().value) return rgba(points_.back());
  const auto upper = std::upper_bound(points_.begin(), points_.end(), value,
                                      [](double v, const TransferPoint& p) { return v < p.value; });
  const TransferPoint& b = *upper;
  const TransferPoint& a = *(upper - 1);
  const double t = (value - a.value) / (b.value - a.value);
  const std::array<double, 4> ca = rgba(a), cb = rgba(b);
  std::array<double, 4> out;
  for (int k = 0; k < 4; ++k) out[size_t(k)] = ca[size_t(k)] + t * (cb[size_t(k)] - ca[size_t(k)]);
  return out;
}

TransferFunction transfer_preset(const std::string& name, const ScalarVolume& volume) {
  if (name == "ct")
    return TransferFunction({{-1000, {0, 0, 0}, 0},
                             {-200, {0.55, 0.25, 0.15}, 0},
                             {-60, {0.85, 0.6, 0.45}, 0.01},
                             {60, {0.8, 0.3, 0.25}, 0.03},
                             {200, {0.95, 0.85, 0.7}, 0.08},
                             {400, {1, 0.98, 0.92}, 0.6},
                             {3000, {1, 1, 1}, 0.9}});
  if (name == "mri") {
    std::vector<float> sorted(volume.values);
    double p = 1;
    if (!sorted.empty()) {
      const size_t k = std::min(sorted.size() - 1, size_t(0.99 * double(sorted.size())));
      std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
      p = sorted[k];
    }
    if (!(p > 0)) p = 1;
    return TransferFunction({{0, {0, 0, 0}, 0},
                             {0.1 * p, {0.25, 0.2, 0.2}, 0},
                             {0.3 * p, {0.7, 0.5, 0.45}, 0.02},
                             {0.6 * p, {0.95, 0.85, 0.75}, 0.12},
                             {p, {1, 1, 1}, 0.5}});
  }
  throw InvalidInput("transfer_preset: unknown transfer preset '" + name + "' (ct, mri)");
}

TransferFunction load_transfer_table(const std::string& path) {
  const char* f = "load_transfer_table";
  constexpr size_t kMaxTableBytes = size_t(16) << 20;  // a table is a few lines
  const std::string text = read_file(path, f, "transfer table", kMaxTableBytes);
  std::istringstream lines(text);
  std::string line;
  std::vector<TransferPoint> points;
  for (int number = 1; std::getline(lines, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string bad = "'" + path + "' line " + std::to_string(number) + ": ";
    std::istringstream in(line);
    TransferPoint p;
    double rgb[3];
    std::string rest;
    require(bool(in >> p.value >> rgb[0] >> rgb[1] >> rgb[2] >> p.opacity) && !(in >> rest), f,
            bad + "expected 'VALUE R G B OPACITY'");
    require(std::isfinite(p.value), f, bad + "the value is not finite");
    require(points.empty() || p.value > points.back().value, f,
            bad + "the values must increase from line to line");
    for (int k = 0; k < 3; ++k) {
      require(rgb[k] >= 0 && rgb[k] <= 255, f, bad + "a colour outside [0, 255]");
      p.colour[size_t(k)] = rgb[k] / 255;
    }
    require(p.opacity >= 0 && p.opacity <= 1, f, bad + "an opacity outside [0, 1]");
    points.push_back(p);
  }
  require(!points.empty(), f, "'" + path + "': no control point");
  return TransferFunction(std::move(points));
}

TransferFunction transfer_function(const std::string& spec, const ScalarVolume& volume) {
  if (spec.empty()) {
    const bool hounsfield =
        std::any_of(volume.values.begin(), volume.values.end(), [](float v) { return v < -200; });
    return transfer_preset(hounsfield ? "ct" : "mri", volume);
  }
  if (spec == "ct" || spec == "mri") return transfer_preset(spec, volume);
  require(std::filesystem::is_regular_file(spec), "transfer_function",
          "unknown transfer '" + spec + "': not a preset (ct, mri) or a table file");
  return load_transfer_table(spec);
}

}  // namespace geolens
