#pragma once
// The geometric lens measured against the classic lenses on the same footing: it is solved, the
// seven classic lenses are matched to the zoom it measured, and every warp is measured by the
// same code (what `geolens compare` reports), its pictures and its text, and the footprint sweep.

#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/render.h"
#include "geolens/source/source_file.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

// What a user sees of each lens: how its focus is magnified, how far the context moves.

/// Per lens, measured on a WarpMesh whose screen is framed at the source's size.
struct FocusMeasure {
  /// Over the focus (the triangles whose source centroid lies in the region): the area-weighted
  /// mean magnification, max / min magnification (1 = uniform), and the shape distortion
  /// s1 / s2 - 1, area-weighted mean and max.
  ///@{
  double zoom = 0, uniformity = 0, shape_mean = 0, shape_max = 0;
  ///@}
  /// sqrt(A / pi), A the source area (pixels^2) of the triangles nearest this lens (by distance
  /// to its region) whose magnification departs from 1 by more than 5 % or whose shape
  /// distortion exceeds 0.05: the radius of the disk the lens disturbs as much.
  double footprint_radius = 0;
  /// The largest |screen - source| (pixels) of a mesh vertex nearest this lens and beyond every
  /// footprint (outside every focus group's disk of radius reach + margin, focus_lens.h, in the
  /// frame a thin region is solved in, stretched_frame.h): 0 when everything beyond the
  /// footprints is left in place.
  double displacement_beyond_footprint = 0;
};

/// Measures every lens on `warp` (its source in source pixels, its screen framed at the source's
/// size), with `measures` = measure_triangles(warp). A region that holds no triangle centroid is
/// measured on the triangle under its peak. Throws InvalidInput if that lies in no triangle.
std::vector<FocusMeasure> measure_foci(const WarpMesh& warp, const TriangleDistortion& measures,
                                       const std::vector<Lens>& lenses);

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

/// What compare_lenses returns: the geometric lens's solve and every method, the geometric lens
/// and the classic lenses matched to it, measured by the same code.
struct Comparison {
  ///@{
  int width = 0, height = 0;  ///< the source's size, pixels
  ///@}
  std::vector<Lens> lenses;  ///< as given
  LensResult geometric;      ///< the geometric lens's solve
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

// The trade-off a lens pays: its largest shape distortion against its footprint, for the focus
// lens and every classic lens of the same focus and footprint, with the radial bound.

/// One method at one footprint ratio.
struct SweepPoint {
  std::string method;           ///< "geometric" or a classic lens's name (classic_lens.h)
  double ratio = 0;             ///< footprint ratio F
  double zoom = 0;              ///< mean magnification over the lens's region
  double uniformity = 0;        ///< max / min magnification over the region
  double shape_max = 0;         ///< largest s1 / s2 - 1 of the whole warp
  double footprint_radius = 0;  ///< pixels, FocusMeasure
};

/// What footprint_sweep returns: per footprint ratio, the radial bounds at the zoom the focus
/// lens reached and what each method measured.
struct Sweep {
  std::vector<double> ratios;     ///< the footprint ratios swept
  std::vector<double> bound;      ///< per ratio, radial_distortion_bound at the zoom reached
  std::vector<double> rim_bound;  ///< per ratio, rim_distortion_bound at the zoom reached
  /// Per ratio in `ratios` order: "geometric" (the focus lens), then for a circle every classic
  /// lens in kClassicLenses order.
  std::vector<SweepPoint> points;
};

/// The footprint ratios a sweep of a lens of `zoom` takes by default (`geolens compare --sweep`):
/// zoom + 1, 1.5, 2, 3 and 4 x zoom, ascending, without repeats.
std::vector<double> sweep_ratios(double zoom);

/// Solves `lens` with the focus model (its other options from `options`) at every footprint
/// ratio in `ratios` (each > the lens's zoom) on a width x height image, and, for a circle, every
/// classic lens with the footprint as radius and a flat top of the region's size, matched to the
/// zoom the focus lens reached (classic_lens.h; `baseline_mesh` vertices along the long side).
/// Throws InvalidInput for an invalid lens or ratio.
Sweep footprint_sweep(double width, double height, const Lens& lens, LensOptions options,
                      const std::vector<double>& ratios, int baseline_mesh = 200);

/// A plot of the sweep: largest shape distortion against the footprint ratio, one polyline per
/// method (its points filled where the focus is uniform, max / min <= 1.01, hollow otherwise)
/// and the bound in black; a legend. RGB, width x height pixels (>= 320 x 240).
Image plot_sweep(const Sweep& sweep, int width = 720, int height = 480);

// The pictures of a comparison: each method's output and shape-distortion
// heat map, and the panel of every method side by side around the lenses.

/// The panel tile side must be in [64, 1024] pixels; throws InvalidInput naming `function`.
void require_panel_tile(int tile, const char* function);

/// The method's output: its warp rendered from `source` (the comparison's, framed at its size;
/// render(WarpMesh, SourceFile, RenderOptions)) at the comparison's size, RGB.
Image comparison_output(const Comparison& comparison, const ComparedMethod& method,
                        const SourceFile& source);

/// The method's shape distortion s1 / s2 - 1 per triangle over `output` (comparison_output),
/// blue 0 to red `heat_max` (> 0), flipped triangles black, with a scale titled
/// "NAME: shape distortion s1/s2 - 1" below (heatmap, annotate.h): RGB, the output's width, taller.
Image comparison_heatmap(const ComparedMethod& method, const Image& output, double heat_max);

/// The input (lenses outlined, a few notes below), then every method: a cell each with four label
/// lines (name, zoom at the first lens, largest shape distortion, area hidden and flips), its
/// output and its heat map below (tile x tile each); four cells per row, the colour scale
/// (0 to `heat_max`, > 0) below. Every picture shows the same square, 1.3 times the extent of the
/// targets' disks. RGB, 4 (tile + 6) + 6 pixels wide; rows = ceil((methods + 1) / 4) of
/// 4 L + 2 tile + 24 pixels (L = 22 for tile >= 176, else 11), plus 6 pixels and the scale.
/// `source` as for comparison_output. Throws InvalidInput for `tile` outside [64, 1024].
Image comparison_panel(const Comparison& comparison, const SourceFile& source, double heat_max,
                       int tile = 256);

// A comparison and a footprint sweep as text: JSON (2-space
// indented, newline at the end) and Markdown, what `geolens compare` writes.

/// {"methods": [...]}, one object per method in order: `name`, `zoom_center` (zoom_measured[0]),
/// `focus_uniformity` (the largest over the lenses of `focus.uniformity` below: over the region
/// given), `distortion` {`focus`, `transition`,
/// `context`, `overall`: {`mean`, `max`} shape distortion, null in a zone with no triangle},
/// `occluded_percent`, `flipped`, and `lenses`: per lens the same object as run_stats_json's
/// lenses without `height` and `zoom_fit` (`kind`, `bbox`, `peak`, `size`, `center` and
/// `radius` for circles, `profile`, `zoom_requested`, `zoom_measured` on this method's warp,
/// `footprint`, `focus` {`zoom`, `uniformity`, `shape_mean`, `shape_max`}, `footprint_radius`,
/// `displacement_beyond_footprint`).
std::string comparison_json(const Comparison& comparison);

/// The same as Markdown under the heading "# geolens compare: `title`" (the input's name): per
/// lens its disk and zooms, the shape distortion per zone, the area distortion per zone, the
/// per-lens focus measures, and the geometric lens's Eq. 7 energy.
std::string comparison_markdown(const Comparison& comparison, const std::string& title);

/// {"points": [...]}, per point of the sweep (in its order): `method`, `ratio`, `zoom`,
/// `uniformity`, `shape_max`, `footprint_radius` and the ratio's `bound`.
std::string sweep_json(const Sweep& sweep);

/// The sweep as a Markdown table under "# geolens compare --sweep: `title`": per ratio the zoom
/// the geometric lens reached, the bound, and each method's largest shape distortion (its focus
/// uniformity in brackets where above 1.01). Throws InvalidInput if a ratio has no "geometric"
/// point.
std::string sweep_markdown(const Sweep& sweep, const std::string& title);

}  // namespace geolens
