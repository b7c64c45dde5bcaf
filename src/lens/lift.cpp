#include "lens/lift.h"

#include <cmath>
#include <string>

#include "geolens/core/errors.h"

namespace geolens {

double lens_height(const Lens& lens, double h0, const Eigen::Vector2d& p) {
  const double t = lens.region.depth(p);
  if (t <= 0) return 0.0;
  return h0 * lens.region.thickness(p) / lens.region.size() * profile_value(lens.profile, t);
}

namespace {

// Overlapping lenses combine by the 4-norm of their heights: where one is 0 it is the other's,
// and unlike the max it leaves no crease where two are equal (its gradient is continuous).
double fourth_power(double x) { return (x * x) * (x * x); }
double fourth_root(double x) { return std::sqrt(std::sqrt(x)); }

}  // namespace

double lift_height(const std::vector<Lens>& lenses, const std::vector<double>& heights,
                   const Eigen::Vector2d& p) {
  require(heights.size() == lenses.size(), "lift_height", "one height per lens expected");
  double sum = 0;
  for (size_t k = 0; k < lenses.size(); ++k)
    sum += fourth_power(lens_height(lenses[k], heights[k], p));
  return fourth_root(sum);
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
  out.log_zoom = Eigen::VectorXd::Zero(n);
  out.inside.assign(size_t(n), 0);
  for (size_t k = 0; k < lenses.size(); ++k) {
    require(std::isfinite(heights[k]) && heights[k] >= 0, "lift",
            "height must be finite and >= 0, got " + std::to_string(heights[k]));
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d p = V.row(i).transpose();
      const double depth = lenses[k].region.depth(p);
      if (depth <= 0) continue;
      const Region& region = lenses[k].region;
      const double level =  // lens_height / h0, without computing the depth again
          region.thickness(p) / region.size() * profile_value(lenses[k].profile, depth);
      out.inside[size_t(i)] = 1;
      out.level(i) = std::max(out.level(i), level);
      // Sums of powers here, their roots below.
      out.V(i, 2) += fourth_power(heights[k] * level);
      out.log_zoom(i) += fourth_power(heights[k] * level / region.size());
    }
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!out.inside[size_t(i)]) continue;
    out.V(i, 2) = fourth_root(out.V(i, 2));
    out.log_zoom(i) = fourth_root(out.log_zoom(i));
  }
  return out;
}

}  // namespace geolens
