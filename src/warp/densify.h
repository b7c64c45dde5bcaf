#pragma once
// Polylines densified before they are mapped, so that a straight segment bends with the warp.

#include <Eigen/Core>

namespace geolens {

/// The most rows densify() returns, and map_features makes in all: 2^22 (64 MiB of coordinates;
/// 15 million vertices took 1.9 GB on their way to a GeoJSON file).
constexpr Eigen::Index kMaxDensifiedRows = Eigen::Index(1) << 22;

/// `path` with vertices added on every segment longer than `max_segment`: a segment a-b of
/// length L is cut into n = ceil(L / max_segment) equal parts, its new vertices a + (k / n)(b - a)
/// for k = 1 .. n - 1. The vertices of `path` are kept exactly (bit for bit) and in order, so a
/// closed ring stays closed.
/// @param path  #P x 2, pixels
/// @param max_segment  pixels, > 0; +infinity returns `path` unchanged
/// Throws InvalidInput naming "densify" if max_segment is not > 0 or a row of `path` is not
/// finite, InvalidOption "max_segment" if the result would have more than kMaxDensifiedRows rows.
Eigen::MatrixX2d densify(const Eigen::MatrixX2d& path, double max_segment);

}  // namespace geolens
