#pragma once
// What a user sees of each lens: how its focus is magnified, how far the context moves.

#include <vector>

#include "geolens/lens/lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// Per lens, measured on a WarpMesh whose screen is framed at the source's size.
struct FocusMeasure {
  /// Over the focus (the triangles whose source centroid lies in the region): the area-weighted
  /// mean magnification, max / min magnification (1 = uniform), and the shape distortion
  /// s1 / s2 - 1, area-weighted mean and max.
  double zoom = 0, uniformity = 0, shape_mean = 0, shape_max = 0;
  /// sqrt(A / pi), A the source area (pixels^2) of the triangles nearest this lens (by distance
  /// to its region) whose magnification departs from 1 by more than 5 % or whose shape
  /// distortion exceeds 0.05: the radius of the disk the lens disturbs as much.
  double footprint_radius = 0;
  /// The largest |screen - source| (pixels) of a mesh vertex nearest this lens and beyond every
  /// footprint (outside every focus group's disk of radius reach + margin, focus_lens.h): 0
  /// when everything beyond the footprints is left in place.
  double displacement_beyond_footprint = 0;
};

/// Measures every lens on `warp` (its source in source pixels, its screen framed at the source's
/// size), with `measures` = measure_triangles(warp). A region that holds no triangle centroid is
/// measured on the triangle under its peak. Throws InvalidInput if that lies in no triangle.
std::vector<FocusMeasure> measure_foci(const WarpMesh& warp, const TriangleDistortion& measures,
                                       const std::vector<Lens>& lenses);

}  // namespace geolens
