#pragma once
// The geometric lens measured against the classic lenses on the same footing: it is solved, the
// seven classic lenses are matched to the zoom it measured, and every warp is measured by the
// same code (what `geolens compare` reports; its pictures are in comparison_images.h, its text
// in comparison_report.h).

#include <string>
#include <vector>

#include "geolens/eval/focus_measure.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/measure/distortion_regions.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// The radius of the classic lenses matched to `lens`, and of the disk its regions are measured
/// in (measure_regions): for the focus model its footprint, footprint_ratio(lens) x reach
/// (focus_lens.h), else its region's size. Pixels.
double classic_radius(const Lens& lens, const LensOptions& options);

/// The classic lens matched to `lens` at `zoom` (>= 1): centred on its peak, classic_radius in
/// size; for the focus model its flat top shows the region at full zoom (focus fraction
/// min(0.95, zoom / footprint ratio)), else the default fraction (kFocusFraction).
CircleLens classic_target(const Lens& lens, const LensOptions& options, double zoom);

/// The methods compare_lenses measures, in its order: "geometric", then every classic lens in
/// kClassicLenses order (to_string(ClassicLens)). The classic lenses are radial: for a polygon or
/// a mask they are fitted to the region's disk (about its peak, radius its reach), which their
/// flat top shows at full zoom. Throws InvalidInput naming `function` when two lenses' classic
/// disks (classic_radius) overlap: the classic lenses do not compose. Decides a tool's output
/// files before any work.
std::vector<std::string> comparison_methods(const std::vector<Lens>& lenses,
                                            const LensOptions& options,
                                            const char* function = "comparison_methods");

/// The outline drawn dashed around a lens (source pixels, a closed loop without its closing
/// vertex): for the focus model its footprint (the region scaled by footprint_ratio about its
/// peak, focus_lens.h) where the region has an outline (a polygon, a mask blob traced as one),
/// else the disk of classic_radius about the peak (a circle's footprint; for the lift models the
/// disk measured).
std::vector<Eigen::Vector2d> footprint_outline(const Lens& lens, const LensOptions& options);

/// One method of a comparison and what was measured on it.
struct ComparedMethod {
  std::string name;  ///< "geometric" or a classic lens's name
  WarpMesh warp;     ///< framed at the source's size
  /// per lens: magnification_at its peak over zoom_measure_radius (distortion.h), the measure
  /// the classic lenses are matched on; [0] is the report's "zoom at centre"
  std::vector<double> zoom_measured;
  TriangleDistortion measures;     ///< measure_triangles(warp)
  RegionStatistics regions;        ///< per zone of the targets (measure_regions)
  std::vector<FocusMeasure> foci;  ///< per lens, over the region given (measure_foci)
};

struct Comparison {
  int width = 0, height = 0;  ///< the source's size, pixels
  std::vector<Lens> lenses;   ///< as given
  LensResult geometric;       ///< the geometric lens's solve
  /// per lens: classic_target at the zoom the geometric lens measured (at least 1); the zones
  /// of every method are taken in these disks
  std::vector<CircleLens> targets;
  std::vector<std::vector<Eigen::Vector2d>> footprints;  ///< per lens: footprint_outline
  std::vector<ComparedMethod> methods;                   ///< comparison_methods(lenses) order
  /// The paper's Eq. 7 energy of the geometric lens's flattening (eq7_energy, summed over the
  /// solved mesh: with a local extent the patch), pixels^2.
  double eq7_energy = 0;
};

/// Solves `lenses` with the geometric lens on a width x height source (`options`), then builds
/// each classic lens matched to the zoom it measured
/// (match_classic_lens over zoom_measure_radius, on a grid of `baseline_mesh` vertices along the
/// long side) and measures every warp: triangles, zones of the targets, foci of the lenses.
/// Throws InvalidInput for an invalid lens, option or size, overlapping disks
/// (comparison_methods) or baseline_mesh outside [4, 1000]; SolverError if a solve fails.
Comparison compare_lenses(int width, int height, const std::vector<Lens>& lenses,
                          const LensOptions& options, int baseline_mesh = 200);

/// The shape distortion drawn red by default: the largest s1 / s2 - 1 over every method's
/// measured triangles, or 1 if that is 0.
double comparison_heat_max(const Comparison& comparison);

}  // namespace geolens
