#pragma once
// The geometric lens: grid -> lift -> harmonic texture -> local/global flattening -> frame.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geolens/geometry/grid.h"
#include "geolens/geometry/subdivide.h"
#include "geolens/lens/flatten.h"
#include "geolens/lens/lift.h"
#include "geolens/lens/texture_map.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

struct FocusField;  // focus_lens.h

/// Which part of the image takes part in the solve.
enum class Extent {
  kGlobal,  ///< the whole image: the context everywhere gives way to the lens
  /// a square patch of side 2 * extent_factor * size around the lenses (clipped to the image),
  /// its border pinned; the rest of the image is the identity. The patch grid has `mesh`
  /// vertices along its long side whatever the image size, so the cost depends on the lens.
  kLocal,
};
Extent parse_extent(const std::string& name);  ///< "global" | "local"
std::string to_string(Extent extent);

/// What a lens magnifies and how (docs/design.md, "Focus lenses" and "Lens models").
enum class LensModel {
  /// The region is the focus: magnified as a whole by its zoom (a similarity, translated to fit
  /// but not rotated), the context giving way within the lens's footprint, with its shape
  /// distortion bounded, and unchanged beyond (focus_lens.h). The solved area is the footprints'
  /// bounding box, so the mesh moves with the lens.
  kFocus,
  /// The paper's: the flattening keeps the shapes of the lifted triangles and the texture is
  /// re-mapped harmonically onto the bump. A long region's lift is a ridge, magnified across
  /// only.
  kLift,
  /// The lift read as a field of log magnification (Lifted::log_zoom): the flattening keeps
  /// each planar triangle's shape scaled by it, the texture is not re-mapped. A region of any
  /// shape reaches its zoom at its peak, junctions included; a thinner part asks for less
  /// (log zoom grows with the local half-width), and a long thin arm still widens more than
  /// it lengthens.
  kField,
  kAuto,  ///< kLift when every lens is a circle, else kField
};
LensModel parse_lens_model(const std::string& name);  ///< "focus" | "lift" | "field" | "auto"
std::string to_string(LensModel model);

struct LensOptions {
  int mesh = 100;  ///< grid vertices along the solved area's long side, in [4, 1000]
  Extent extent = Extent::kGlobal;  ///< kLift and kField only (kFocus solves its footprints)
  double extent_factor = 2.5;       ///< local patch half-side over the lens size (radius), > 1
  LensModel model = LensModel::kFocus;
  TextureWeights texture = TextureWeights::kCotan;
  SubdivisionOptions subdivision;
  FlattenOptions flatten;
  /// kLift and kField: bump heights are calibrated until every lens's measured zoom is within
  /// this relative tolerance of its request, or `max_calibration_solves` full solves were made.
  double zoom_tolerance = 0.02;
  int max_calibration_solves = 12;
};

/// Throws InvalidInput unless the options are in range.
void validate(const LensOptions& options);

/// Wall-clock milliseconds per stage, summed over the calibration solves.
struct StageTimings {
  double lift = 0, texture = 0, factorize = 0, iterate = 0, total = 0;
};

struct LensResult {
  LensModel model = LensModel::kLift;  ///< the model used (kAuto resolved)
  WarpMesh warp;                       ///< source = texture coordinates, screen = framed flattening
  PlanarMesh mesh;                     ///< the (subdivided) planar mesh the lift was built on
  Eigen::AlignedBox2d box;             ///< the solved area: the image, or the local patch
  Eigen::MatrixX3d lifted;             ///< #V x 3 the lifted mesh of the final solve, pixels
  Eigen::MatrixX2d flat;               ///< #V x 2 the flattening before framing, pixels
  FlattenResult flattening;            ///< iterations and energies of the final solve
  /// per lens: calibrated centre height h0, pixels; for kFocus the log zoom of its focus
  std::vector<double> heights;
  std::vector<double> zoom_measured;  ///< per lens: magnification at its region's peak
  /// per lens (kFocus): the largest zoom that fits where the lens is (fitting_zoom in
  /// focus_lens.h); a lens that asks for more is solved at this zoom. Empty for other models.
  std::vector<double> zoom_fits;
  /// The cotan texture map folded and was redone with non-negative weights (cotan+).
  bool texture_fallback = false;
  int solves = 0;  ///< full solves made by the calibration
  StageTimings timings;
};

/// Magnifies lenses on a width x height image. Holds the grid. solve() is independent of any
/// earlier call; update() is the interactive path a GUI loop calls every frame: it keeps the
/// flattener (and its symbolic factorization) while the mesh's topology stays, starts a focus
/// lens from its power-law start and the other models from the previous frame's flattening and
/// heights, and skips subdivision.
class GeometricLens {
 public:
  GeometricLens(double width, double height, const LensOptions& options = {});

  /// kFocus: magnifies each lens's region by its zoom, or by the largest zoom that fits where it
  /// is (`zoom_fits`), in one solve. kLift and kField: finds each lens's bump height so that its
  /// measured zoom matches its request (zoom 1 means height 0, the identity). Returns the final
  /// warp. Throws InvalidInput for an invalid lens, SolverError if a system cannot be solved.
  LensResult solve(const std::vector<Lens>& lenses) const;

  /// Like solve() for lenses that moved or changed since the last update(), reusing what did not
  /// change (see the class comment); the result stays valid until the next update(). Its zoom
  /// and convergence are checked as in solve(); its mesh is the base grid.
  const LensResult& update(const std::vector<Lens>& lenses);

  /// One solve with given peak heights (pixels), no calibration; fills `zoom_measured`.
  LensResult solve_with_heights(const std::vector<Lens>& lenses,
                                const std::vector<double>& heights) const;

  /// The grid of the whole image (global extent).
  const Grid& grid() const { return grid_; }
  double width() const { return width_; }
  double height() const { return height_; }

 private:
  Eigen::AlignedBox2d solved_box(const std::vector<Lens>& lenses) const;
  Grid base_grid(const std::vector<Lens>& lenses, Eigen::AlignedBox2d& box) const;
  LensModel model_for(const std::vector<Lens>& lenses) const;
  // The lenses to solve, and the grid (over `box`) to solve them on. kFocus: each zoom lowered
  // to the largest that fits (footprints kept), those zooms in `fits`; other models: the lenses
  // as they are.
  std::vector<Lens> fitted(const std::vector<Lens>& lenses, std::vector<double>& fits, Grid& grid,
                           Eigen::AlignedBox2d& box) const;
  LensResult solve_on(const Grid& grid, const Eigen::AlignedBox2d& box,
                      const std::vector<Lens>& lenses, const std::vector<double>& heights) const;
  FlattenOptions flatten_options(LensModel model) const;
  Lifted lift_and_texture(const std::vector<Lens>& lenses, const std::vector<double>& heights,
                          const PlanarMesh& mesh, const Eigen::AlignedBox2d& box,
                          std::chrono::steady_clock::time_point start, LensResult& r,
                          FocusField& focus) const;
  void texture(const Lifted& lifted, LensResult& r) const;
  void finish(const std::vector<Lens>& lenses, const Lifted& lifted, LensResult& r) const;
  LensResult solve_cached(const Grid& grid, const Eigen::AlignedBox2d& box,
                          const std::vector<Lens>& lenses, const std::vector<double>& heights);
  LensResult calibrate(const std::vector<Lens>& lenses, std::vector<double> heights,
                       const std::function<LensResult(const std::vector<double>&)>& run) const;

  double width_, height_;
  LensOptions options_;
  Grid grid_;
  struct Cache {
    std::unique_ptr<Flattener> flattener;
    Eigen::MatrixX2d flat;       // the last flattening, the next update's starting point
    Eigen::MatrixX2d change;     // what the last update changed in it (#V x 2, or empty)
    Eigen::MatrixX2d predicted;  // flat + change: the candidate start of this update's first solve
    Eigen::AlignedBox2d box;     // the area it covers
    std::vector<char> pinned;    // the flattener's pinned vertices (kFocus)
    Eigen::MatrixX3i faces;      // its triangles (a circle's ringed grid depends on the lens)
    LensModel model = LensModel::kFocus;  // the flattener's
    std::vector<Lens> lenses;
    LensResult result;
  } cache_;
};

}  // namespace geolens
