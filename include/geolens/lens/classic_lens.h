#pragma once
// The classic focus+context lenses as WarpMeshes, for comparison with the geometric lens:
// zoom-in, Sarkar-Brown fisheye, a C1 fisheye, bifocal, and flat-top lenses with linear and
// raised-cosine drop-off.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "geolens/geometry/grid.h"
#include "geolens/lens/lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/warp/warp_mesh.h"

namespace geolens {

/// Every classic lens here is radial and leaves everything outside its radius r in place. It is
/// given, like the sigma lenses of Pietriga and Appert 2008, as the source point a screen point
/// shows: a screen point at distance D = u r from the lens centre shows the source point on the
/// same ray at distance T(u) r, T increasing, T(u) = u for u >= 1. Its magnification at the
/// centre is 1 / T'(0) = z, the lens's zoom; a = CircleLens::focus_fraction (0.5) is the inner
/// radius of the lenses that have one, as a fraction of r, on screen.
enum class ClassicLens {
  /// An inset magnifier (a loupe): the screen disk of radius r shows the source disk of radius
  /// r / z magnified z times and hides the ring r / z < |p - c| < r under it.
  /// T(u) = u / z for u < 1: a jump at the rim.
  kZoomIn,
  /// Sarkar and Brown 1992 (Graphical fisheye views of graphs, CHI '92), polar form: a source
  /// point at normalized distance t goes to G(t) = (d + 1) t / (d t + 1), d = z - 1. Its inverse
  /// T(u) = u / (1 + d (1 - u)) is a sigma-lens gain falling linearly from z at the centre to 1
  /// at the rim. C0 at the rim (G'(1) = 1 / z), where its shape distortion is d.
  kFisheye,
  /// The fisheye made C1 at the rim: T(u) = u / (1 + d (1 - u)^2), the Sarkar-Brown gain with its
  /// drop-off squared so its slope is 0 at the rim (our choice, documented in classic_lens.cpp).
  kFisheyeSmooth,
  /// The bifocal display (Spence and Apperley 1982, Data base navigation: an office environment
  /// for the professional; radial form as surveyed by Leung and Apperley 1994, A review and
  /// taxonomy of distortion-oriented presentation techniques): two uniform scales, z on the
  /// screen disk a r and one uniform radial compression between a r and r. T(u) = u / z for
  /// u <= a, then linear from a / z to 1.
  kBifocal,
  /// Flat-top lens with linear drop-off (the sigma-lens family, Pietriga and Appert 2008, Sigma
  /// lenses, CHI '08; Carpendale and Montagnese 2001's drop-off functions): gain M = z on the
  /// screen disk a r, falling linearly to 1 at r; T(u) = u / M(u).
  kFlattopLinear,
  /// Flat-top lens with raised-cosine drop-off: M = 1 + (z - 1) (1 + cos(pi (u - a) / (1 - a))) / 2
  /// between a r and r: C1 at both ends of the drop-off.
  kFlattopCosine,
  /// The best radial lens for its proportions: uniform zoom z on the screen disk a r, then the
  /// power-law ring rho = R (s / R)^k (source s, screen rho, R = r), k = 1 - ln z / ln(z / a),
  /// whose shape distortion 1 / k - 1 is the same everywhere in the ring and is the least any
  /// radial lens with that focus and outer radius can have (radial_distortion_bound in
  /// focus_lens.h). T(u) = u / z for u <= a, u^(1 / k) from a to 1.
  kPowerRing,
};

/// Every classic lens, in the order the comparison reports them.
constexpr std::array<ClassicLens, 7> kClassicLenses = {
    ClassicLens::kZoomIn,   ClassicLens::kFisheye,       ClassicLens::kFisheyeSmooth,
    ClassicLens::kBifocal,  ClassicLens::kFlattopLinear, ClassicLens::kFlattopCosine,
    ClassicLens::kPowerRing};

/// "zoom_in" | "fisheye" | "fisheye_smooth" | "bifocal" | "flattop_linear" | "flattop_cosine" |
/// "power_ring"
std::string to_string(ClassicLens lens);
/// The lens of that name (to_string); throws InvalidInput naming the names for any other.
ClassicLens parse_classic_lens(const std::string& name);

/// T(u): the normalized source distance shown at normalized screen distance u >= 0 by a lens of
/// zoom z >= 1 and focus fraction a in (0, 1) (see ClassicLens). Throws InvalidInput for u < 0,
/// z < 1, a outside (0, 1) or non-finite values.
double classic_source_distance(ClassicLens lens, double u, double zoom, double a = kFocusFraction);

/// A circle the mesh must follow: no triangle crosses it.
struct Ring {
  Eigen::Vector2d center;  ///< pixels
  double radius;           ///< pixels, > 0
};

/// make_grid(width, height, vertices_long_side), then made to follow every ring: each ring in
/// turn, grid vertices closer to it than 0.2 cell are moved onto it along the ray from its centre
/// (image-border vertices and vertices already on an earlier ring stay), then every triangle
/// the circle still crosses is split along it, at the exact circle points of the crossed edges
/// (one vertex per edge, shared by both triangles of the edge). Afterwards every vertex of a
/// triangle lies on one side of each ring or on it, so a jump or a kink of a radial map at a ring
/// is represented. Rings closer than about a cell to each other or to an image side give thin
/// triangles but no crossing. The sides flags mark the vertices on the rectangle's sides.
PlanarMesh ringed_grid(double width, double height, int vertices_long_side,
                       const std::vector<Ring>& rings);

/// The classic lens `kind` on a width x height source, as a WarpMesh framed at the source's
/// size. The mesh is ringed_grid(width, height, vertices_long_side, rings at a r and r of every
/// lens) taken as *screen* positions; each vertex's source position is the lens's point function
/// T evaluated there (identity outside every lens). zoom_in duplicates the vertices on each rim
/// so that its inset (inside) and the context (outside) meet on screen without sharing source
/// positions; the ring it hides is then in no triangle. Each lens uses its own zoom.
/// Throws InvalidInput for an invalid lens (validate(CircleLens)), a centre outside the image,
/// overlapping lens disks, or vertices_long_side outside [4, 1000].
WarpMesh classic_warp(ClassicLens kind, const std::vector<CircleLens>& lenses, double width,
                      double height, int vertices_long_side = 200);

/// Finds each lens's zoom parameter z such that magnification_at(warp, centre,
/// measure_radius[k]) (distortion.h, the same measure as the geometric lens's zoom_measured)
/// equals targets[k].zoom within 0.5 % (secant steps on log z, at most 20 builds), and returns
/// the warp built with them (zoom_parameter: the z per lens, zoom_measured: the measure at its
/// centre). A lens whose gain peaks at the centre (the fisheyes) needs a z above
/// the target, because the measure averages a small disk around the centre.
/// @param measure_radius  per lens, pixels (> 0)
Magnification match_classic_lens(ClassicLens kind, const std::vector<CircleLens>& targets,
                                 const std::vector<double>& measure_radius, double width,
                                 double height, int vertices_long_side = 200);

}  // namespace geolens
