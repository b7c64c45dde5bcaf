#include "support/polygon_reference.h"

#include <algorithm>
#include <limits>

namespace geolens::testing {

bool brute_inside(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y() > p.y()) != (poly[j].y() > p.y()) &&
        p.x() < poly[j].x() + (p.y() - poly[j].y()) * (poly[i].x() - poly[j].x()) /
                                  (poly[i].y() - poly[j].y())) {
      in = !in;
    }
  }
  return in;
}

double brute_boundary_distance(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - a - t * (b - a)).norm());
  }
  return best;
}

}  // namespace geolens::testing
