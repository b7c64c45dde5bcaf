#pragma once
// A lens: the region it magnifies, the zoom asked, its footprint (and the lift's bump shape), and
// the checks every face makes of it.

#include "geolens/geometry/roi.h"
#include "geolens/lens/profile.h"

namespace geolens {

/// One lens: where, how much, and with which bump shape.
struct Lens {
  Region region;
  double zoom = 2.0;  ///< requested magnification at the region's peak, in [1, 8]
  Profile profile = Profile::kGaussian;
  /// LensModel::kFocus: how far the context may give way, as the ratio of the footprint's reach
  /// to the region's from its peak (focus_lens.h); 0 for the default, 2 zoom. Else > zoom, <= 100.
  double footprint = 0;
};

/// The zooms a lens may ask for.
constexpr double kMinZoom = 1, kMaxZoom = 8;
/// Throws InvalidInput, naming `function`, unless `zoom` is in [kMinZoom, kMaxZoom].
void require_zoom(double zoom, const char* function);

/// Throws InvalidInput unless the lens is usable on a width x height image: zoom in [1, 8], a
/// circle's centre or every polygon vertex inside the image, footprint 0 or in (zoom, 100].
void validate_lens(const Lens& lens, double width, double height);

}  // namespace geolens
