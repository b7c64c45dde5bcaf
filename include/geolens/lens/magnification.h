#pragma once
// The result every lens method returns (lens_method.h).

#include <vector>

#include "geolens/warp/warp_mesh.h"

namespace geolens {

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
