#pragma once
// Private: the focus lens of elongated regions solved in a stretched frame (docs/design.md,
// "Thin regions: a stretched frame"). A ring about a point has, on the rays across a thin
// region, the region's extent along it (its envelope), so the room above and below a line of text
// limits it long before its magnified focus fills that room. Solved in a frame stretched across
// the region by S = diag(sx, sy), the ring is conjugated, x -> S^-1 f(S x): a uniform zoom about a
// point commutes with S, so the focus is still magnified exactly by its zoom, unrotated; the
// ring across the region takes 1 / s of the room it took; and the image stays a rectangle.

#include <Eigen/Core>
#include <vector>

#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"

namespace geolens {

/// The stretch of the frame `lenses` are solved in: per lens, along y for a region with an
/// outline (a polygon, a traced mask blob: Region::outline) wider than tall, along x for one
/// taller than wide, by 1 up to a bounding box of aspect kStretchFrom and kMostStretch from
/// kStretchFull, a smoothstep between (so the zoom a lens gets is continuous in its shape);
/// (1, 1) for a circle or a region without an outline. Of all lenses, the least along each axis
/// (one circle anywhere keeps the frame). Continuous in the lenses' shapes, and the same
/// wherever they are.
Eigen::Vector2d frame_stretch(const std::vector<Lens>& lenses);

/// The aspect from which a polygon is stretched, to which it is stretched in full, and by how
/// much then.
constexpr double kStretchFrom = 4, kStretchFull = 8, kMostStretch = 1.5;

/// `lenses` in the frame stretched by `stretch`, each region the polygon of its outline stretched
/// (every region has one where frame_stretch stretches); as they are for a stretch of (1, 1).
std::vector<Lens> stretched(const std::vector<Lens>& lenses, const Eigen::Vector2d& stretch);

/// A result solved in the frame stretched by `stretch`, in the image's pixels: its warp (source
/// and screen), mesh, box and flattening divided by the stretch, the warp framed at
/// `screen_width` x `screen_height`. Zooms are the frame's (a zoom commutes with the stretch).
void unstretch(LensResult& result, const Eigen::Vector2d& stretch, int screen_width,
               int screen_height);

}  // namespace geolens
