#pragma once
// A lens: the region it magnifies, the zoom asked, its footprint (and the lift's bump shape), and
// the checks every face makes of it.

#include <string>
#include <vector>

#include "geolens/geometry/roi.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

// Bump profiles: the shape of a lens's 3D lift across its region of interest.

/// Profile of the lift, as a function of the normalized depth t in [0, 1] (0 on the ROI
/// boundary, 1 at its centre / medial axis). Every profile is 0 at t = 0, 1 at t = 1 and
/// continuous, so the lift is `h0 * profile(t)` with h0 the height at the centre.
enum class Profile {
  kGaussian,  ///< (exp(-s^2 / sigma^2) - exp(-1 / sigma^2)) / (1 - exp(-1 / sigma^2)), s = 1 - t,
              ///< sigma = 0.4: the paper's gaussian, normalized to 0 at the rim (DESIGN 2.4)
  kSphere,    ///< sqrt(1 - s^2): the paper's hemisphere, scaled to height h0
  kMesa,      ///< flat top for t >= 0.5, smoothstep wall 3u^2 - 2u^3 (u = 2t) below
};

/// profile(t) for t in [0, 1]; t is clamped to that range.
double profile_value(Profile profile, double t);

/// Parses "gaussian", "sphere" or "mesa"; throws InvalidInput otherwise.
Profile parse_profile(const std::string& name);
/// The name parse_profile reads: "gaussian", "sphere" or "mesa".
std::string to_string(Profile profile);

/// One lens: where, how much, and with which bump shape.
struct Lens {
  Region region;      ///< what it magnifies, source pixels
  double zoom = 2.0;  ///< requested magnification at the region's peak, in [1, 8]
  Profile profile = Profile::kGaussian;  ///< the lift's bump shape (lift and field models)
  /// LensModel::kFocus: how far the context may give way, as the ratio of the footprint's reach
  /// to the region's from its peak (focus_lens.h); 0 for the default, 2 zoom. Else > zoom, <= 100.
  double footprint = 0;
};

/// The zooms a lens may ask for.
///@{
constexpr double kMinZoom = 1, kMaxZoom = 8;
///@}
/// Throws InvalidInput, naming `function`, unless `zoom` is in [kMinZoom, kMaxZoom].
void require_zoom(double zoom, const char* function);

/// Throws InvalidInput unless the lens is usable on a width x height image: zoom in [1, 8], a
/// circle's centre or every polygon vertex inside the image, footprint 0 or in (zoom, 100].
void validate_lens(const Lens& lens, double width, double height);

// The result every lens method returns (lens_method.h).

/// A lens method's answer: the warp, and per lens what it was asked to build and what it built.
struct Magnification {
  WarpMesh warp;  ///< source = source pixels, screen = framed at the source's size
  /// per lens: the zoom the method was built with (the geometric lens's zoom after fitting, a
  /// classic lens's matched zoom parameter)
  std::vector<double> zoom_parameter;
  /// per lens: the magnification measured at its region's peak (magnification_at over
  /// zoom_measure_radius, distortion.h)
  std::vector<double> zoom_measured;
  /// A draft (LensSession::update with draft): solved on a mesh that was not refined where the
  /// focus lens's ring bends (LensOptions::mesh_tolerance); the same lenses solved in full may
  /// move points by a pixel or two.
  bool draft = false;
};

}  // namespace geolens
