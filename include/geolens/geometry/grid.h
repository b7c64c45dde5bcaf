#pragma once
// The regular triangle grid the geometric lens deforms.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace geolens {

/// Which image sides a grid vertex lies on (bit flags).
enum Side : uint8_t { kLeft = 1, kRight = 2, kTop = 4, kBottom = 8 };

/// A planar triangle mesh covering the image, a manifold disk whose border lies on the image
/// sides.
struct PlanarMesh {
  Eigen::MatrixX2d V;          ///< #V x 2 vertex positions, pixels
  Eigen::MatrixX3i F;          ///< #F x 3 triangles, (b - a) x (c - a) > 0
  std::vector<uint8_t> sides;  ///< #V Side flags, 0 for interior vertices
};

/// A regular grid of nearly square cells covering [0, width] x [0, height], each cell split into
/// two triangles with alternating diagonals so no direction is favoured.
struct Grid : PlanarMesh {
  int columns = 0;  ///< vertices per row
  int rows = 0;     ///< vertices per column
  double cell = 0;  ///< mean cell side, pixels
};

/// Builds the grid for a width x height image (pixels, > 0) with `vertices_long_side`
/// vertices along the longer side (>= 2); the shorter side gets as many as keep cells nearly
/// square (at least 2).
Grid make_grid(double width, double height, int vertices_long_side);

/// The range every lens accepts for its grid's vertices along the long side.
///@{
constexpr int kMinMeshVertices = 4, kMaxMeshVertices = 1000;
///@}
/// Throws InvalidOption (core/errors.h), naming `function` and `option`, unless
/// `vertices_long_side` is in [kMinMeshVertices, kMaxMeshVertices].
void require_mesh_vertices(int vertices_long_side, const char* function,
                           const char* option = "mesh");

}  // namespace geolens
