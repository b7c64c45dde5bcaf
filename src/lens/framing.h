#pragma once
// Private: a flattening put on the screen (GeometricLens's last stage).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geolens/geometry/grid.h"
#include "geolens/lens/lens_options.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// The flattening X (#V x 2, pixels) on a width x height screen: sliding and fixed borders
/// already fill the image and are returned as they are; a free flattening is scaled uniformly to
/// fit and centred.
Eigen::MatrixX2d frame(const Eigen::MatrixX2d& X, Boundary boundary, double width, double height);

/// Triangulates the image rectangle (width x height) outside the local patch `box`, whose border
/// vertices are those of `mesh` with non-zero sides, as the identity, conforming to the patch
/// border: four trapezoids, each fanned from its two outer corners. Appends the four image
/// corners and the triangles to `warp`, whose first rows are `mesh`'s vertices.
void add_identity_frame(WarpMesh& warp, const PlanarMesh& mesh, const Eigen::AlignedBox2d& box,
                        double width, double height);

}  // namespace geolens
