#pragma once
// The focus lens (LensModel::kFocus): the region given is magnified as a whole, by a similarity,
// and the context gives way only within a finite footprint around it (docs/design.md, "Focus
// lenses"). Two properties of the engine, tested by sweeps (tests/lens/focus_lens_test.cpp):
// the zoom a lens gets, and the warp, are continuous functions of each lens's place, size and
// zoom and of the other lenses (where one ring gives way to another near a side the two are
// blended, FocusGroup::blend; magnify_near_side holds the fits so the zoom has no step), and
// asking for more never gives less (each lens is solved at the largest zoom up to the one asked
// at which it fits, fitting_zooms). Where they do not hold yet (a mask without an outline near a
// side, the mesh's own resolution): docs/design.md, "Weak, and next".

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geolens/geometry/grid.h"
#include "geolens/lens/lens.h"
#include "geometry/conforming_mesh.h"
#include "lens/flatten.h"

namespace geolens {

class ThreadPool;  // core/thread_pool.h: the functions below that take one run their
                   // per-vertex loops on it

/// The footprint of a lens as a ratio: the footprint is the focus scaled by it about the lens's
/// centre (along each ray, R = ratio r_f), within the disk of radius ratio x reach.
/// `lens.footprint`, or 2 zoom if that is 0 (the proportions of a flat-top lens whose flat top
/// is half its radius, docs/design.md).
double footprint_ratio(const Lens& lens);

/// The sharpest corner of a region's outline a mesh is made to follow, degrees.
constexpr double kSharpestMeshedCorner = 5;

/// Whether the focus lens's grid of cell side `cell` (pixels) follows the lenses: when every lens
/// is a circle of radius at least 2 cells or an outline (a polygon, a traced mask blob) spanning a
/// cell with no corner sharper than kSharpestMeshedCorner, GeometricLens makes its grid follow
/// every region's boundary and every footprint's edge (focus_curves), so no triangle crosses
/// them; otherwise the focus is blended over a band of cells (focus_band).
bool meshed_along_regions(const std::vector<Lens>& lenses, double cell);

/// How far outside a region a mesh vertex of cell side `cell` still counts as in its focus,
/// pixels (the "band" of the functions below): sqrt(2) cells on a grid that does not follow the
/// regions, so that every triangle that meets a region is whole in its focus; a millionth of a
/// cell on one that does (meshed_along_regions).
double focus_band(const std::vector<Lens>& lenses, double cell);

/// The curves a focus lens's mesh follows (conform_mesh), pixels: the boundary of every region
/// (a circle or a polygon) and the edge of every group's footprint, where focus_start's ring
/// meets the identity, as it is found for a grid of cell `cell` and focus band `band` on a
/// width x height image.
std::vector<MeshCurve> focus_curves(const std::vector<Lens>& lenses, double cell, double band,
                                    double width, double height);

/// The least maximum shape distortion s1 / s2 - 1 of any radial lens that magnifies a disk of
/// radius r_f uniformly by `zoom` and leaves everything beyond R = ratio r_f in place:
/// 1 / (1 - ln zoom / ln ratio) - 1, reached by the power-law ring rho = R (s / R)^k,
/// k = 1 - ln zoom / ln ratio (in u = ln s, v = ln rho the ring must lower v - u by ln zoom over
/// ln ratio, and its distortion is 1 / (dv/du) - 1). Infinite when ratio <= zoom.
double radial_distortion_bound(double zoom, double ratio);

/// The maximum shape distortion of the focus lens's ring (focus_start) for the same disk, zoom
/// and ratio: its profile ends at the footprint's edge without a crease (a radial scale reaching
/// 1 with slope 0, docs/design.md, "A rim without a crease"), for which it compresses a little
/// more within: (1 + b a) / k - 1, a = ln zoom / ln ratio, k = 1 - a, b = 0.3 up to a = 0.55,
/// falling to 0 at a = 0.85 (where the ring has least room it is the power law), so at most 1.3
/// times radial_distortion_bound. Infinite when ratio <= zoom.
double rim_distortion_bound(double zoom, double ratio);

/// The mesh a focus is fitted and warped on, pixels: its cell's side, and the band its foci are
/// held wider where the mesh does not follow the regions (focus_band). The default, a cell of 0
/// and no band, is a mesh that follows every region: its foci are the regions' own extents (the
/// footprints the solved box holds, from which the mesh's cell follows).
struct FitMesh {
  double cell = 0, band = 0;
};

/// Lenses whose rings would not fit side by side (disks of reach x zoom^1.25, reach + ring_need,
/// around their peaks overlap; a superset of those whose magnified foci would overlap) are
/// magnified together, as one focus: the union of their regions, at the largest of their zooms,
/// about the centre of their peaks, or where the regions cross a side of the width x height image
/// (pixels), about the point of that side nearest it (so the side stays); its reach is the
/// farthest point of any of the regions from the centre, its footprint the largest ratio of
/// theirs. A lens alone is a group of one. A group of circles near a side (`slides`, off every
/// side) has a footprint grown as if it were magnified about a point between its centre and the
/// side, the side's point where it touches it (so the footprint does not jump there); a lens
/// alone within a tenth of its reach of a side, or nearer than 1.5 reaches where that fits more
/// or a circle's slide would take its focus most of the way there, is magnified about the side's
/// point as if it touched it, and one over a side near another about their corner (most_zoom).
/// Footprints do not overlap: where the disks of radius reach + margin of two groups would, the
/// room between their foci is shared, each given what its ring needs at its zoom and half of what
/// is left (less where the other needs more), so no lens moves another and every margin is
/// continuous in the lenses' places and zooms (a lens with a near neighbour fits a lower zoom;
/// GeometricLens gives lenses near each other their zooms first, docs/design.md "Several lenses
/// share room").
struct FocusGroup {
  std::vector<size_t> lenses;  ///< the members, indices into the lenses
  Eigen::Vector2d centre;      ///< the peak of a lens alone, pixels
  /// The point the ring is about, pixels: the centre, or where a region crosses an image side
  /// the point of that side nearest it (the focus is magnified about it, so the side stays).
  Eigen::Vector2d fixed;
  bool on_side = false;  ///< a region crosses (or touches) an image side
  /// The magnified focus may slide where its ring has too little room (focus_start): a group of
  /// circles off every side, away from them, or crossing one side, along it, and a lens alone
  /// over one side (or magnified about its point), along it (docs/design.md, "Sliding").
  bool slides = false;
  double reach = 0;  ///< pixels
  /// The footprint (the focus scaled by the ratio about `fixed`) lies in the disk of radius
  /// reach + margin about the centre, pixels.
  double margin = 0;
  double log_zoom = 0;  ///< the focus's
  /// The most zoom a circle near a side fits, below its ring's own fit where that is held so that
  /// the zoom is continuous from its slide off the side to the ring about the side's point, and
  /// the direction to that side (docs/design.md, "Sliding").
  double most_zoom = std::numeric_limits<double>::infinity();
  Eigen::Vector2d side = Eigen::Vector2d::Zero();
  /// A lens of the nearest group whose footprint made this group's margin shrink (the most), -1
  /// if none did.
  int neighbour = -1;
  /// Where a lens near a side goes over from its own ring to the ring about the side's point (or
  /// the corner), that ring's group, null if none: the warp is the blend of the two, the blend's
  /// ring weighed blend_weight in (0, 1) at blend_zoom times the zoom, this group's 1 -
  /// blend_weight at (1 - blend_weight blend_zoom) / (1 - blend_weight) times it, so the focus is
  /// magnified by the zoom about a point between theirs and the warp is continuous
  /// (docs/design.md, "The blend of two rings").
  std::shared_ptr<const FocusGroup> blend;
  double blend_weight = 0, blend_zoom = 1;
  /// The radius of the disk about the centre that holds the footprint (of the blend's too),
  /// pixels.
  double disk_radius() const;
};
/// The groups of `lenses` at `log_zooms`, on `mesh`: a lens's choice of rings near a side
/// measures them as the fit and the warp do on that mesh (a mask blob held sqrt 2 cells wider by
/// the mesh, fitted by a choice that saw it unwidened, was shown unmagnified 35 px from a side
/// and 1.58 at 34). Which lenses are grouped does not depend on the mesh.
std::vector<FocusGroup> focus_groups(const std::vector<Lens>& lenses,
                                     const std::vector<double>& log_zooms, double width,
                                     double height, const FitMesh& mesh);
/// The same at the lenses' own zooms.
std::vector<FocusGroup> focus_groups(const std::vector<Lens>& lenses, double width, double height,
                                     const FitMesh& mesh);
/// All of `lenses` (at their own zooms) as one group, alone: its footprint's own margin.
FocusGroup focus_group_of(const std::vector<Lens>& lenses, double width, double height,
                          const FitMesh& mesh);

/// How far beyond a focus of extent `reach` (pixels) its footprint's edge must lie for a ring
/// at `log_zoom` to fit (the radial bound's distortion at most 4): reach (zoom^1.25 - 1), pixels.
double ring_need(double reach, double log_zoom);

/// Whether the image border (width x height, pixels) is too far from `group`'s footprint to round
/// its edge anywhere: 1.3 times the group's disk (radius reach + margin) from its centre or more.
/// Such a group's footprint, and the mesh that follows it, are the same wherever it is.
bool footprint_clear_of_border(const FocusGroup& group, double width, double height);

/// Per lens, the largest zoom at which its group fits where it is on a width x height image
/// (pixels), on a mesh of cell side `cell`, with the footprints the lenses have: the footprint's
/// edge along every ray from the group's centre (the image border where nearer), less two cells
/// for the mesh to bend in, must lie far enough beyond the focus that the radial bound's
/// distortion stays at most 4, zoom <= ((edge - 2 cell) / inner)^0.8. A region over an image side
/// is magnified about a point on that side (so the side stays where it is), which shifts the
/// magnified focus inward; a focus that slides (FocusGroup::slides) has its ring's radial to
/// tangential scale, with the least slide that makes it at least 0.2 on every ray, at least 0.2
/// (a distortion of 4). With `reasons`, per lens what bounds the edge on the ray that limits
/// it, and a remedy: "the image's top side, 12 px from the region (...)", "lens 2 beside it
/// (...)" (its footprint stops where a neighbour's begins) or "its footprint (...)" (its ratio).
/// GeometricLens solves each lens at
/// the largest zoom up to the one asked at which this holds with the lens's own footprint at
/// that zoom (a lens asking for more gets no less, and one that fits gets exactly its zoom).
/// With `only`, the fits of the groups holding those lenses alone (the others' are 0): a search
/// for one group's zoom among 200 lenses evaluated every group's ring at each step. In a
/// stretched frame (stretched_frame.h), `stretch` (its pixels per image pixel along x and y)
/// turns the distances the reasons name into the image's pixels.
std::vector<double> fitting_zooms(const std::vector<Lens>& lenses, double cell, double band,
                                  double width, double height,
                                  std::vector<std::string>* reasons = nullptr,
                                  const std::vector<size_t>* only = nullptr,
                                  const Eigen::Vector2d& stretch = Eigen::Vector2d::Ones());
/// The zoom at which `group` of `lenses` fits, as fitting_zooms tells it, with the margin the
/// group has.
double group_fitting_zoom(const FocusGroup& group, const std::vector<Lens>& lenses, double cell,
                          double band, double width, double height);

/// What the focus lens asks of the flattening at the vertices `V` (#V x 2, pixels) of a mesh of
/// cell side `cell` (pixels) on a width x height image, lens i with log zoom `log_zooms[i]`
/// (>= 0):
struct FocusField {
  std::vector<FocusGroup> groups;  ///< focus_groups of the lenses
  /// Focus: every vertex within `band` of a region (so every triangle that meets the
  /// region is whole in its focus), with the index of the nearest group. Pinned: every vertex
  /// that no group's ring (focus_start) moves, on or beyond every footprint's edge. Anisotropy:
  /// the distortion of the ring the vertex is deepest in, at the vertex (the power law's along
  /// its ray, less within the rim, 1 at the footprint's edge), times `slack`.
  FocusConstraints constraints;
  Eigen::VectorXd log_scale;  ///< #V the group's log zoom in its focus, 0 elsewhere
  Eigen::VectorXd level;      ///< #V 1 where the vertex may move, 0 where pinned
  /// #V x 2 each vertex moved by the ring it is deepest in: focus_map at the log zooms, pixels.
  Eigen::MatrixX2d start;
};
FocusField focus_field(const Eigen::MatrixX2d& V, const std::vector<Lens>& lenses,
                       const std::vector<double>& log_zooms, double cell, double band, double width,
                       double height, ThreadPool& pool, double slack = 1.1);

/// focus_start's map without its repair of folds, as a function of any points (#P x 2 in,
/// #P x 2 out, pixels), which runs on `pool` (it must outlive the function).
std::function<Eigen::MatrixX2d(const Eigen::MatrixX2d&)> focus_map(
    const std::vector<Lens>& lenses, const std::vector<FocusGroup>& groups, double cell,
    double band, double width, double height, ThreadPool& pool);

/// The vertices of `mesh`, made for lenses `from` (over the box `from_box`, cell side
/// `from_cell`, pixels) to follow focus_curves as conform_mesh's `on_curve` records, moved with
/// the lenses to `to` (the same lenses moved by one translation; box `to_box`, cell `to_cell`),
/// pixels. A vertex in a group's footprint keeps its ray from the ring's centre and its place
/// rho = (s - inner) / (edge - inner) between the focus and the footprint's edge, where that edge
/// moved to along the ray (so it moves rigidly in a focus, and along the border where the edge
/// is the border); one beyond every edge turns within two cells of it to the box's stretch; one
/// on a side of the box takes the stretch across the side, so it stays on it, and slides along
/// it; one on a footprint's edge goes onto the moved edge. None where a triangle would keep less
/// than a fifth of its area (a sliver of under a hundredth of a cell's area may shrink further, but
/// not fold). #V x 2.
std::optional<Eigen::MatrixX2d> moved_focus_mesh(const PlanarMesh& mesh,
                                                 const std::vector<int>& on_curve,
                                                 const std::vector<Lens>& from,
                                                 const Eigen::AlignedBox2d& from_box,
                                                 double from_cell, const std::vector<Lens>& to,
                                                 const Eigen::AlignedBox2d& to_box, double to_cell,
                                                 double width, double height, ThreadPool& pool);

/// A fold-free first flattening for focus_field's constraints: each group's power-law ring,
/// generalized to any region. About the group's centre c (or a point on the image side its
/// regions cross), along each ray the focus reaches inner (a smooth envelope of the regions'
/// extent plus the band) and the footprint's edge lies at R (the focus scaled by the footprint
/// ratio, within the group's disk, short of the image border where that is nearer); a point at
/// distance t from c and d from the regions goes to c + g (p - c) with
/// ln g = log_zoom P(x), x = ln(R / s) / ln(R / inner), s = max(t, inner + max(d - band, 0)):
/// the power law P = x but for its rim, where P's slope falls to 0 at the edge so that the ring
/// ends there without a crease (rim_distortion_bound; docs/design.md, "A rim without a crease").
/// s >= t and ds/dt <= 1 make g t grow along every ray while R > zoom inner, so no triangle
/// folds (in the continuum), the focus is magnified exactly, and the image border maps onto
/// itself. For a circle this is the power ring with its rim. Where the ring has too little room
/// on the rays towards a side (FocusGroup::slides), the magnified focus slides away from it (or,
/// about a side's point, along that side) by the least v that gives every ray's power law a
/// radial to tangential scale of at least 0.2: a point moves by w v more,
/// w = (1 - g s / R) / (1 - zoom inner / R) (1 in the focus, which is then magnified about
/// c - v / (zoom - 1), 0 at the edge), which scales that scale along each ray by one factor,
/// 1 - v.u / (R - zoom inner) (the rim fades as |v| nears half of R - zoom inner); the image
/// border, beyond the edge, stays. The groups are applied one after the other;
/// their footprints do not overlap. Where a triangle of `mesh` still folds (near a polygon's
/// corner, where the start has a cone that a wide triangle averages badly), the vertices of
/// folded triangles outside the foci move to the mean of their neighbours, a few rounds, then
/// half way back to their source places; where a fold is left, the same from the unrepaired
/// start with a sliver's vertices going back from the first round (slivers of the mesh where a
/// footprint's edge meets an image side at a glancing angle).
/// Returns #V x 2, pixels.
Eigen::MatrixX2d focus_start(const PlanarMesh& mesh, const std::vector<Lens>& lenses,
                             const std::vector<FocusGroup>& groups, double cell, double band,
                             double width, double height, ThreadPool& pool);

/// Per lens, the largest zoom of its group (its own, or exp of 0.8, 0.6, 0.4 or 0.2 of its log)
/// at which the group's ring in focus_start folds no triangle of `mesh` (cell side `cell`,
/// pixels, on a width x height image), 1 if none: where fitting_zooms's estimate is too much for
/// the mesh (a ring a few cells wide).
std::vector<double> unfolding_zooms(const PlanarMesh& mesh, const std::vector<Lens>& lenses,
                                    double cell, double band, double width, double height,
                                    ThreadPool& pool);

/// Flattens focus lenses with `flattener` (built on `field`, focus_field's constraints and log
/// scales for `mesh`, Standard::kScaled, kCotan weights) from focus_start (`field.start`,
/// repaired), each triangle's anisotropy bound raised to the start's distortion where that is
/// higher (Flattener::admit_anisotropy: where the rings of several groups overlap); if the
/// flattener does not admit that start (a fold on the mesh, a fixed vertex moved), from the
/// start at 0.8, 0.6, 0.4, 0.2 of the log zooms, else from the identity (the mesh's vertices).
/// `control` as in Flattener::solve.
FlattenResult flatten_focus(Flattener& flattener, const PlanarMesh& mesh,
                            const std::vector<Lens>& lenses, const FocusField& field, double cell,
                            double band, double width, double height, ThreadPool& pool,
                            const SolveControl* control = nullptr);

}  // namespace geolens
