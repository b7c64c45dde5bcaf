#include "lens/stretched_frame.h"

#include <algorithm>
#include <optional>

namespace geolens {

namespace {

// 1 up to an aspect of kStretchFrom, kMostStretch from kStretchFull, a smoothstep between.
double stretch_of_aspect(double aspect) {
  const double z = std::clamp((aspect - kStretchFrom) / (kStretchFull - kStretchFrom), 0.0, 1.0);
  return 1 + (kMostStretch - 1) * z * z * (3 - 2 * z);
}

}  // namespace

Eigen::Vector2d frame_stretch(const std::vector<Lens>& lenses) {
  Eigen::Vector2d out = Eigen::Vector2d::Constant(lenses.empty() ? 1.0 : kMostStretch);
  for (const Lens& lens : lenses) {
    if (!lens.region.outline()) return Eigen::Vector2d::Ones();
    const Eigen::Vector2d size = lens.region.bounds().sizes();
    out = out.cwiseMin(Eigen::Vector2d(stretch_of_aspect(size.y() / size.x()),
                                       stretch_of_aspect(size.x() / size.y())));
  }
  return out;
}

std::vector<Lens> stretched(const std::vector<Lens>& lenses, const Eigen::Vector2d& stretch) {
  std::vector<Lens> out = lenses;
  if (stretch == Eigen::Vector2d::Ones()) return out;
  for (Lens& lens : out) {
    std::vector<Eigen::Vector2d> v = lens.region.outline().value();
    for (Eigen::Vector2d& p : v) p = p.cwiseProduct(stretch);
    lens.region = Region::polygon(v);
  }
  return out;
}

void unstretch(LensResult& r, const Eigen::Vector2d& stretch, int screen_width, int screen_height) {
  const Eigen::RowVector2d inverse = stretch.cwiseInverse().transpose();
  for (Eigen::MatrixX2d* m : {&r.warp.source, &r.warp.screen, &r.mesh.V, &r.flat, &r.flattening.X})
    m->array().rowwise() *= inverse.array();
  if (r.lifted.rows() > 0) r.lifted.leftCols<2>().array().rowwise() *= inverse.array();
  r.box =
      Eigen::AlignedBox2d(r.box.min().cwiseQuotient(stretch), r.box.max().cwiseQuotient(stretch));
  r.warp.screen_width = screen_width;
  r.warp.screen_height = screen_height;
}

}  // namespace geolens
