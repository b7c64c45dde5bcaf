#pragma once
// Writing meshes as Wavefront OBJ, for inspection and independent checks.

#include <Eigen/Core>
#include <string>

namespace geolens {

/// Writes `V` (#V x 2 or #V x 3; a 2D mesh gets z = 0) and `F` (#F x 3, 0-based) as OBJ
/// (`v x y z` lines, then 1-based `f a b c` lines) with full double precision. Writes to a
/// temporary file and renames it into place; throws IoError if writing fails.
void write_obj(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixX3i& F);

}  // namespace geolens
