#include "warp/densify.h"

#include <cmath>
#include <string>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {

Eigen::MatrixX2d densify(const Eigen::MatrixX2d& path, double max_segment) {
  require(max_segment > 0, "densify",
          "max_segment must be > 0 pixels, got " + number_text(max_segment));
  for (Eigen::Index i = 0; i < path.rows(); ++i)
    require(path.row(i).allFinite(), "densify", "path row " + std::to_string(i) + " is not finite");
  // Parts per segment first, so the result is allocated once and its size checked before.
  std::vector<Eigen::Index> parts(size_t(std::max<Eigen::Index>(path.rows() - 1, 0)));
  Eigen::Index rows = path.rows();
  for (Eigen::Index i = 0; i + 1 < path.rows(); ++i) {
    const double n = std::ceil((path.row(i + 1) - path.row(i)).norm() / max_segment);
    require_option(n < double(kMaxDensifiedRows) && rows + Eigen::Index(n) <= kMaxDensifiedRows + 1,
                   "densify", "max_segment",
                   number_text(max_segment) + " px makes more than " +
                       std::to_string(kMaxDensifiedRows) + " vertices (at segment " +
                       std::to_string(i) + "): take a larger one");
    parts[size_t(i)] = std::max<Eigen::Index>(Eigen::Index(n), 1);
    rows += parts[size_t(i)] - 1;
  }
  Eigen::MatrixX2d out(rows, 2);
  Eigen::Index next = 0;
  for (Eigen::Index i = 0; i < path.rows(); ++i) {
    out.row(next++) = path.row(i);
    if (i + 1 == path.rows()) break;
    const Eigen::Index n = parts[size_t(i)];
    for (Eigen::Index k = 1; k < n; ++k)
      out.row(next++) = path.row(i) + (double(k) / double(n)) * (path.row(i + 1) - path.row(i));
  }
  return out;
}

}  // namespace geolens
