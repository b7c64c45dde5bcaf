#pragma once
// Private: the two ways GeometricLens solves (docs/architecture.md, "lens/"). A LensPipeline is
// chosen once, when the lens is made, from LensOptions::model: FocusPipeline (focus_pipeline.h,
// kFocus: the region magnified as a whole, fitted where it is, one solve) or LiftPipeline
// (lift_pipeline.h, kLift, kField and kAuto: the paper's lift, its zoom calibrated by repeated
// solves). Each owns its steps; GeometricLens and LensSession call the steps below and never
// branch on the model.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/solve_control.h"
#include "geolens/geometry/grid.h"
#include "geolens/lens/geometric_lens.h"
#include "lens/flatten.h"
#include "lens/lift.h"
#include "lens/solve_cache.h"

namespace geolens {

class LensPipeline;
class ThreadPool;
struct SolveCache;

/// What a pipeline is given: the image it solves on, the options and the lens's thread pool.
struct LensContext {
  double width = 0, height = 0;      ///< the image, pixels
  LensOptions options;               ///< validated
  Grid grid;                         ///< the whole image's grid (global extent)
  std::shared_ptr<ThreadPool> pool;  ///< every parallel loop of a solve runs here
};

/// The lenses to solve and the mesh to solve them on (LensPipeline::fitted).
struct FittedLenses {
  std::vector<Lens> lenses;  ///< validated; kFocus: each at the zoom it is solved at
  BaseMesh mesh;             ///< the mesh before the lift's subdivision
  Eigen::AlignedBox2d box;   ///< the area it covers, pixels
  /// kFocus: per lens, the zoom fitted, what limits it (empty where it is the zoom asked) and
  /// whether the mesh held it back (LensResult's fields of the same names). Empty otherwise.
  std::vector<double> zoom_fits;
  std::vector<std::string> zoom_fit_reasons;
  bool mesh_limited = false;
  /// kFocus: where the lenses are solved in a stretched frame (stretched_frame.h), the pipeline
  /// of that frame and its stretch; `lenses`, `mesh` and `box` are then the frame's. Null: the
  /// image's own.
  std::shared_ptr<const LensPipeline> frame;
  Eigen::Vector2d stretch = Eigen::Vector2d::Ones();
};

class LensPipeline {
 public:
  explicit LensPipeline(LensContext context) : c_(std::move(context)) {}
  virtual ~LensPipeline() = default;

  /// The pipeline of `context.options.model`.
  static std::unique_ptr<LensPipeline> make(LensContext context);

  const LensContext& context() const { return c_; }

  /// The model that solves `lenses` (kAuto resolved).
  virtual LensModel model_for(const std::vector<Lens>& lenses) const = 0;

  /// The lenses validated, at the zooms they are solved at, and the mesh for them. With a cache,
  /// a pipeline may reuse the mesh it left there (a lens that only moved). A draft's mesh is not
  /// refined.
  virtual FittedLenses fitted(const std::vector<Lens>& lenses, SolveCache* cache,
                              bool draft) const = 0;

  /// The heights a calibration of `fit`'s lenses starts from (one per lens, as `calibrated`
  /// takes them): 0 for a lens of zoom 1, else `known(k)` where that has one (a session's
  /// heights of the same lens last frame), else the model's first guess (initial_height).
  std::vector<double> start_heights(
      const FittedLenses& fit,
      const std::function<std::optional<double>(size_t)>& known = nullptr) const;

  /// The lenses' mesh with no fitting (solve_with_heights): `lenses` as given.
  virtual FittedLenses unfitted(const std::vector<Lens>& lenses) const = 0;

  /// The mesh solved for the heights `h` (one per lens): the grid, or the lift's subdivision of
  /// it.
  virtual PlanarMesh solved_mesh(const FittedLenses& fit, const std::vector<double>& h) const = 0;

  /// The solve of `fit`'s lenses on `mesh` from the heights `h` (one per lens, pixels; kFocus:
  /// log zooms) until each lens's zoom is met (calibration), refitting the flattener in `cache`
  /// or building it (by the fit's frame where it has one, the result then in the image's
  /// pixels). Fills the fit's zooms and reasons in the result.
  LensResult calibrated(const FittedLenses& fit, const PlanarMesh& mesh,
                        const std::vector<double>& h, SolveCache& cache,
                        const SolveControl& control) const;

  /// One solve of `lenses` on `mesh` (over `box`) with the heights `h`, no calibration: lifts it
  /// (kFocus: reads its focus field), maps the texture, flattens with the cache's flattener and
  /// frames the result. `solve` numbers it for `control`'s progress.
  virtual LensResult solve_once(const Eigen::AlignedBox2d& box, const std::vector<Lens>& lenses,
                                const PlanarMesh& mesh, const std::vector<double>& h,
                                SolveCache& cache, const SolveControl& control,
                                int solve) const = 0;

 protected:
  using Clock = std::chrono::steady_clock;
  static double ms_since(Clock::time_point start);
  /// The cache's flattener refitted to `lifted` (same topology) or built anew, the cache's last
  /// flattening moved with the solved box; fills r.timings.factorize from `start`.
  void prepare_flattener(const Lifted& lifted, const FocusConstraints& constraints,
                         const FlattenOptions& options, LensResult& r, SolveCache& cache) const;

  /// The end of every solve: `flatten` (the model's iterations from the cache's flattener, given
  /// `control` with its progress numbered by the calibration's `solve`), its result kept as the
  /// next solve's start (a prediction is used once), timed; then the framed WarpMesh (`boundary`
  /// as flattened), the zoom measured at each lens's peak and the total time since `start`.
  void flatten_and_finish(const std::function<FlattenResult(const SolveControl&)>& flatten,
                          const std::vector<Lens>& lenses, const Lifted& lifted, Boundary boundary,
                          const SolveControl& control, int solve, Clock::time_point start,
                          SolveCache& cache, LensResult& r) const;

  LensContext c_;
};

/// What a GeometricLens holds: its pipeline, shared by its copies.
struct GeometricLens::Impl {
  std::unique_ptr<LensPipeline> pipeline;
};

}  // namespace geolens
