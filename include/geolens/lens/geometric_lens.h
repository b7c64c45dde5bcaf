#pragma once
// The geometric lens: grid -> lift -> harmonic texture -> local/global flattening -> frame.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/lens.h"
#include "geolens/lens/lens_options.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// Wall-clock milliseconds per stage, summed over the calibration solves.
struct StageTimings {
  double lift = 0;       ///< the lift and its subdivision (kFocus: the focus field)
  double texture = 0;    ///< the harmonic texture map (kFocus: none, the mesh itself)
  double factorize = 0;  ///< the flattener's systems built and factorized
  double iterate = 0;    ///< the local/global iterations
  double total = 0;      ///< the whole solve, the stages above and what lies between
};

/// The geometric lens's answer: the Magnification every lens method returns (the warp's source
/// is the texture coordinates, its screen the framed flattening), and how it was found.
struct LensResult : Magnification {
  LensModel model = LensModel::kLift;  ///< the model used (kAuto resolved)
  PlanarMesh mesh;                     ///< the (subdivided) planar mesh the lift was built on
  Eigen::AlignedBox2d box;             ///< the solved area: the image, or the local patch
  Eigen::MatrixX3d lifted;             ///< #V x 3 the lifted mesh of the final solve, pixels
  Eigen::MatrixX2d flat;               ///< #V x 2 the flattening before framing, pixels
  FlattenResult flattening;            ///< iterations and energies of the final solve
  /// per lens (kLift, kField): the calibrated height h0 of its bump's peak, pixels; empty for
  /// kFocus
  std::vector<double> lift_heights_px;
  /// per lens (kFocus): the natural log of the zoom its focus was solved at (ln zoom_fits); empty
  /// for the other models
  std::vector<double> focus_log_zooms;
  /// per lens (kFocus): the zoom it was solved at, the one asked if that fits where the lens is,
  /// else the largest that does (fitting_zooms in focus_lens.h, and what its mesh holds without
  /// a fold). Empty for other models.
  std::vector<double> zoom_fits;
  /// per lens (kFocus): what limits its zoom where it gets at least 0.1 % less than asked (the
  /// image side, another lens, its footprint or the mesh, as fitting_zooms words it), else empty.
  std::vector<std::string> zoom_fit_reasons;
  /// (kFocus) a lens got less than fits where it is because its ring folds the mesh
  /// (unfolding_zooms): a LensSession then solves a draft as a full frame.
  bool mesh_limited = false;
  /// The cotan texture map folded and was redone with non-negative weights (cotan+).
  bool texture_fallback = false;
  int solves = 0;        ///< full solves made by the calibration
  StageTimings timings;  ///< where the time went, milliseconds
};

/// One line per lens of `lenses` that `result` did not give the zoom asked: "lens K gets zoom Z
/// of the A asked where it is, limited by REASON" (the focus model's zoom_fit_reasons), or
/// "lens K reached zoom Z of the A requested" where the measured zoom misses by more than 10 %.
/// What every face says (the CLI on stderr, Python as warnings).
std::vector<std::string> zoom_warnings(const std::vector<Lens>& lenses, const LensResult& result);

/// Magnifies lenses on a width x height image. Holds the grid and nothing that changes: solve()
/// is independent of any earlier call and may run on several threads at once. The interactive
/// path, which keeps what one frame leaves for the next, is LensSession (lens_session.h).
///
/// How it solves is chosen once, from options.model: the focus model's pipeline (fitted where it
/// is, one solve) or the paper's (lift, texture, flatten, calibrated heights); solve() does not
/// branch on the model (docs/architecture.md).
///
/// Threads: the lens owns one ThreadPool of options.flatten.threads (0 = one per hardware
/// thread), started by the constructor and shared by its copies; every solve runs its parallel
/// loops there (the focus lens's, and the flatteners' it builds). Solves running at once share
/// it: one has the workers, the others run their loops on their own threads (ThreadPool::run).
class GeometricLens {
 public:
  /// A lens on a width x height image (pixels, > 0) with `options` (checked: InvalidInput, or
  /// InvalidOption naming the option); starts its thread pool.
  GeometricLens(double width, double height, const LensOptions& options = {});

  /// kFocus: magnifies each lens's region by its zoom, or by the largest zoom that fits where it
  /// is (`zoom_fits`), in one solve. kLift and kField: finds each lens's bump height so that its
  /// measured zoom matches its request (zoom 1 means height 0, the identity): the mesh is
  /// subdivided once for the first guess of the heights, and every calibration solve after the
  /// first refits the same flattener (symbolic factorization kept) and starts from the last
  /// flattening. Returns the final warp. Throws InvalidInput for an invalid lens, SolverError if
  /// a system cannot be solved, Cancelled if `control` stops it.
  LensResult solve(const std::vector<Lens>& lenses, const SolveControl& control = {}) const;

  /// One solve with given per-lens parameters, no calibration, as a LensResult reports them:
  /// peak heights in pixels (kLift, kField: lift_heights_px) or log zooms (kFocus:
  /// focus_log_zooms); fills `zoom_measured`.
  LensResult solve_with_heights(const std::vector<Lens>& lenses,
                                const std::vector<double>& heights) const;

  /// The grid of the whole image (global extent).
  const Grid& grid() const;
  double width() const;                ///< the image's width, pixels
  double height() const;               ///< the image's height, pixels
  const LensOptions& options() const;  ///< what every solve uses

 private:
  friend class LensSession;  // calls the pipeline's steps with its caches
  struct Impl;               // the pipeline of options.model (src/lens/lens_pipeline.h)
  std::shared_ptr<const Impl> impl_;
};

}  // namespace geolens
