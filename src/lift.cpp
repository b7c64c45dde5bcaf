#include "geolens/lift.h"

#include <cmath>
#include <string>

#include "geolens/errors.h"

namespace geolens {

double CircleRoi::depth(const Eigen::Vector2d& p) const {
  const double d = (p - center).norm();
  return d >= radius ? 0.0 : 1.0 - d / radius;
}

void validate_lens(const Lens& lens, double width, double height) {
  const Eigen::Vector2d& c = lens.roi.center;
  require(c.allFinite(), "validate_lens", "lens centre is not finite");
  require(std::isfinite(lens.roi.radius) && lens.roi.radius > 0, "validate_lens",
          "lens radius must be a positive number, got " + std::to_string(lens.roi.radius));
  require(c.x() >= 0 && c.x() <= width && c.y() >= 0 && c.y() <= height, "validate_lens",
          "lens centre (" + std::to_string(c.x()) + ", " + std::to_string(c.y()) +
              ") is outside the " + std::to_string(int(width)) + "x" + std::to_string(int(height)) +
              " image");
  require(std::isfinite(lens.zoom) && lens.zoom >= 1 && lens.zoom <= 8, "validate_lens",
          "zoom must be in [1, 8], got " + std::to_string(lens.zoom));
}

Lifted lift(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
            const std::vector<double>& heights) {
  require(heights.size() == lenses.size(), "lift", "one height per lens expected");
  Lifted out;
  const Eigen::Index n = V.rows();
  out.V.resize(n, 3);
  out.V.leftCols<2>() = V;
  out.V.col(2).setZero();
  out.level = Eigen::VectorXd::Zero(n);
  out.inside.assign(size_t(n), 0);
  for (size_t k = 0; k < lenses.size(); ++k) {
    require(std::isfinite(heights[k]) && heights[k] >= 0, "lift",
            "height must be finite and >= 0, got " + std::to_string(heights[k]));
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = lenses[k].roi.depth(V.row(i).transpose());
      if (t <= 0) continue;
      const double p = profile_value(lenses[k].profile, t);
      out.inside[size_t(i)] = 1;
      out.level(i) = std::max(out.level(i), p);
      out.V(i, 2) = std::max(out.V(i, 2), heights[k] * p);
    }
  }
  return out;
}

}  // namespace geolens
