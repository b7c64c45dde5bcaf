#pragma once
// One call for every lens: the geometric lens and each classic lens magnify the same `Lens`
// list and return the same result.

#include <memory>
#include <string>
#include <vector>

#include "geolens/lens/classic_lens.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// A way to magnify lenses on a source: the geometric lens (any model) or a classic lens.
/// Stateless: magnify() may run on several threads at once.
class LensMethod {
 public:
  virtual ~LensMethod() = default;
  /// "geometric", or the classic lens's to_string(ClassicLens).
  virtual std::string name() const = 0;
  /// Magnifies `lenses` on a width x height source: the warp (framed at the source's size) and,
  /// per lens, the zoom it was built with and the zoom measured at its region's peak
  /// (magnification_at over zoom_measure_radius, distortion.h). Throws InvalidInput for lenses
  /// the method cannot take, SolverError if a solve fails.
  virtual Magnification magnify(const std::vector<Lens>& lenses, double width,
                                double height) const = 0;
};

/// The geometric lens (GeometricLens::solve with `options`); zoom_parameter is the zoom each lens
/// was solved at (its request, or the largest that fits, LensResult::zoom_fits).
class GeometricMethod final : public LensMethod {
 public:
  /// Throws InvalidInput (InvalidOption) for options out of range (validate(LensOptions)).
  explicit GeometricMethod(const LensOptions& options = {});
  std::string name() const override { return "geometric"; }
  Magnification magnify(const std::vector<Lens>& lenses, double width,
                        double height) const override;
  const LensOptions& options() const { return options_; }  ///< what every solve uses

 private:
  LensOptions options_;
};

/// What a ClassicMethod is built on.
struct ClassicOptions {
  int mesh = 200;  ///< grid vertices along the long side, in [4, 1000]
  /// Per lens, the radius the zoom is measured over (pixels, > 0); empty: zoom_measure_radius of
  /// the region's size on the source's long side at `mesh`. A comparison passes the geometric
  /// lens's, so that every method is matched by the same measure.
  std::vector<double> measure_radius;
};

/// A classic lens reading each `Lens` as the focus model does: its region (a circle) is the
/// focus, shown at the lens's zoom, and its footprint ratio (footprint_ratio, focus_lens.h: 2 x
/// zoom by default) the lens's extent. So the classic lens has radius footprint x r and, where it
/// has a flat top, the focus fraction zoom / footprint (at most 0.95): the flat top shows the
/// region at full zoom. Its zoom parameter is matched so that the measured zoom is the lens's
/// (match_classic_lens). Throws InvalidInput for a region that is not a circle.
class ClassicMethod final : public LensMethod {
 public:
  /// Throws InvalidOption unless options.mesh is in [kMinMeshVertices, kMaxMeshVertices].
  explicit ClassicMethod(ClassicLens kind, ClassicOptions options = {});
  std::string name() const override { return to_string(kind_); }
  Magnification magnify(const std::vector<Lens>& lenses, double width,
                        double height) const override;
  /// The classic lens `magnify` builds for `lens` (its zoom the lens's, before matching).
  static CircleLens circle_lens(const Lens& lens);
  /// The inverse: a Lens that ClassicMethod reads as `circle` (radius, zoom >= 1, fraction).
  static Lens lens_for(const CircleLens& circle);

 private:
  ClassicLens kind_;
  ClassicOptions options_;
};

/// The geometric method with `options`, then each classic lens in kClassicLenses order.
std::vector<std::unique_ptr<LensMethod>> every_method(const LensOptions& options = {},
                                                      const ClassicOptions& classic = {});

}  // namespace geolens
