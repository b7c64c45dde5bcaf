#pragma once
// The trade-off a lens pays: its largest shape distortion against its footprint, for the focus
// lens and every classic lens of the same focus and footprint, with the radial bound.

#include <string>
#include <vector>

#include "geolens/io/image.h"
#include "geolens/lens/geometric_lens.h"

namespace geolens {

/// One method at one footprint ratio.
struct SweepPoint {
  std::string method;           ///< "geometric" or a classic lens's name (classic_lens.h)
  double ratio = 0;             ///< footprint ratio F
  double zoom = 0;              ///< mean magnification over the lens's region
  double uniformity = 0;        ///< max / min magnification over the region
  double shape_max = 0;         ///< largest s1 / s2 - 1 of the whole warp
  double footprint_radius = 0;  ///< pixels, focus_measure.h
};

struct Sweep {
  std::vector<double> ratios;     ///< the footprint ratios swept
  std::vector<double> bound;      ///< per ratio, radial_distortion_bound at the zoom reached
  std::vector<double> rim_bound;  ///< per ratio, rim_distortion_bound at the zoom reached
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

}  // namespace geolens
