#pragma once
// Private: what one solve of GeometricLens leaves for the next (the calibration's next solve, or
// the next frame of a LensSession).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "geolens/geometry/grid.h"
#include "geolens/lens/geometric_lens.h"
#include "lens/flatten.h"

namespace geolens {

/// The mesh a solve starts from, before the lift's subdivision: a grid over the solved area, or
/// (kFocus) that grid made to follow the regions and footprints and refined where the start
/// bends, and so no longer a grid.
struct BaseMesh : PlanarMesh {
  BaseMesh() = default;
  explicit BaseMesh(const Grid& grid) : PlanarMesh(grid), cell(grid.cell) {}
  double cell = 0;  ///< the mean cell side of the grid it was made from, pixels
};

// The focus lens's mesh of one frame (its grid made to follow the regions and footprints and
// refined where the start bends), kept for the next: a lens moved clear of the image border has
// the same mesh, translated, so the next frame neither remeshes nor refactorizes; one whose
// footprint the border cuts, the same mesh deformed with it for a few cells
// (FocusPipeline::moved_mesh).
struct MeshMemo {
  std::vector<Lens> lenses;       // as meshed (fitted) or last moved to
  Eigen::AlignedBox2d box;        // the mesh's
  BaseMesh mesh;                  // the mesh
  std::vector<double> unfolding;  // unfolding_zooms on it when made
  std::vector<int> on_curve;      // conform_mesh's: per vertex, the curve it lies on, or -1
  bool clear = false;             // made with every footprint clear of the image border
  double drift = 0;               // pixels the lenses moved since it was made
};

struct SolveCache {
  MeshMemo mesh;  // kFocus: the last mesh (empty lenses: none)
  std::unique_ptr<Flattener> flattener;
  Eigen::MatrixX2d flat;                // the last flattening, the next solve's starting point
  Eigen::MatrixX2d predicted;           // a better start for the next solve only (or empty)
  Eigen::AlignedBox2d box;              // the area it covers
  std::vector<char> pinned;             // the flattener's pinned vertices (kFocus)
  Eigen::MatrixX3i faces;               // its triangles (a ringed grid depends on the lens)
  LensModel model = LensModel::kFocus;  // the flattener's
};

}  // namespace geolens
