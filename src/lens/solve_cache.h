#pragma once
// Private: what one solve of GeometricLens leaves for the next (the calibration's next solve, or
// the next frame of a LensSession).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "geolens/lens/flatten.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens {

struct SolveCache {
  std::unique_ptr<Flattener> flattener;
  Eigen::MatrixX2d flat;                // the last flattening, the next solve's starting point
  Eigen::MatrixX2d predicted;           // a better start for the next solve only (or empty)
  Eigen::AlignedBox2d box;              // the area it covers
  std::vector<char> pinned;             // the flattener's pinned vertices (kFocus)
  Eigen::MatrixX3i faces;               // its triangles (a ringed grid depends on the lens)
  LensModel model = LensModel::kFocus;  // the flattener's
};

}  // namespace geolens
