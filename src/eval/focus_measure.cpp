#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/warp/warp_map.h"
#include "lens/focus_lens.h"
#include "lens/stretched_frame.h"

namespace geolens {

namespace {

constexpr double kDeparture = 0.05;  // magnification or shape change counted as disturbed

// The lens whose region is nearest to p, and that distance.
std::pair<size_t, double> nearest_lens(const std::vector<Lens>& lenses, const Eigen::Vector2d& p) {
  size_t best = 0;
  double distance = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < lenses.size(); ++k) {
    const double d = lenses[k].region.distance(p);
    if (d < distance) best = k, distance = d;
  }
  return {best, distance};
}

}  // namespace

std::vector<FocusMeasure> measure_foci(const WarpMesh& warp, const TriangleDistortion& measures,
                                       const std::vector<Lens>& lenses) {
  require(measures.magnification.size() == warp.F.rows(), "measure_foci",
          "the measures must be those of the warp's triangles");
  const size_t n = lenses.size();
  std::vector<FocusMeasure> out(n);
  std::vector<double> focus_area(n, 0), lowest(n, std::numeric_limits<double>::infinity()),
      highest(n, 0), disturbed(n, 0);
  for (Eigen::Index f = 0; f < warp.F.rows(); ++f) {
    const Eigen::Vector2d centroid = (warp.source.row(warp.F(f, 0)) +
                                      warp.source.row(warp.F(f, 1)) + warp.source.row(warp.F(f, 2)))
                                         .transpose() /
                                     3.0;
    const auto [k, distance] = nearest_lens(lenses, centroid);
    const double a = measures.source_area(f), m = measures.magnification(f),
                 shape = measures.conformal(f);
    if (std::abs(m - 1) > kDeparture || shape > kDeparture) disturbed[k] += a;
    if (distance > 0) continue;
    FocusMeasure& lens = out[k];
    focus_area[k] += a;
    lens.zoom += a * m;
    lens.shape_mean += a * shape;
    lens.shape_max = std::max(lens.shape_max, shape);
    lowest[k] = std::min(lowest[k], m);
    highest[k] = std::max(highest[k], m);
  }
  // Beyond the footprints: outside every focus group's disk (focus_lens.h), in the frame the
  // lenses are solved in (stretched_frame.h: there an ellipse in the image), on a mesh that
  // follows the regions (the warp does not say its cell). Where the mesh does not follow one (a
  // mask without an outline), its band may move a group near a side to the side's point, whose
  // footprint is larger, and a vertex there would count as beyond: none did on the mask with a
  // hole dragged to a side (test AMaskWithAHoleNearingASideKeepsAContinuousZoom).
  const Eigen::Vector2d stretch = frame_stretch(lenses);
  const std::vector<FocusGroup> groups =
      focus_groups(stretched(lenses, stretch), warp.screen_width * stretch.x(),
                   warp.screen_height * stretch.y(), FitMesh{});
  for (Eigen::Index v = 0; v < warp.source.rows(); ++v) {
    const Eigen::Vector2d p = warp.source.row(v).transpose(), in_frame = p.cwiseProduct(stretch);
    bool beyond = true;
    for (const FocusGroup& g : groups)
      beyond = beyond && (in_frame - g.centre).norm() >= g.disk_radius();
    if (!beyond) continue;
    const size_t k = nearest_lens(lenses, p).first;
    out[k].displacement_beyond_footprint = std::max(
        out[k].displacement_beyond_footprint, (warp.screen.row(v) - warp.source.row(v)).norm());
  }
  std::optional<WarpMap> map;  // built when a region needs it
  for (size_t k = 0; k < n; ++k) {
    if (focus_area[k] == 0) {
      // A region smaller than the mesh's triangles: the one under its peak.
      if (!map) map.emplace(warp);
      const Eigen::Index f = map->source_triangle(lenses[k].region.peak());
      require(f >= 0, "measure_foci",
              "lens " + std::to_string(k + 1) + "'s peak lies in no triangle of the warp");
      focus_area[k] = 1;
      out[k].zoom = lowest[k] = highest[k] = measures.magnification(f);
      out[k].shape_mean = out[k].shape_max = measures.conformal(f);
    }
    out[k].zoom /= focus_area[k];
    out[k].shape_mean /= focus_area[k];
    out[k].uniformity =
        lowest[k] > 0 ? highest[k] / lowest[k] : std::numeric_limits<double>::infinity();
    out[k].footprint_radius = std::sqrt(disturbed[k] / std::numbers::pi);
  }
  return out;
}

}  // namespace geolens
