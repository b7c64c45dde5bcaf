#include "lens/focus_pipeline.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "core/thread_pool.h"
#include "lens/focus_lens.h"
#include "lens/shared_room.h"
#include "lens/solve_cache.h"
#include "lens/stretched_frame.h"

namespace geolens {

namespace {

// The refinement's tolerance relative to a region's reach (base_mesh).
constexpr double kRelativeTolerance = 1.0 / 400;

// The refinement's slope tolerance (MeshRefinement::slope_tolerance) next to a circle's focus
// (focus_curves), where its ring bends most: a triangle the mesh made to follow the circle may
// have an obtuse corner, whose linear map is far more distorted than the ring (a circle r 30 at
// zoom 2, footprint ratio 8: 0.753 against the ring's 0.650). At 0.075 the focus lens of
// docs/reproduction.md's sweep is within 1.11 times its ring's bound (1.05-1.19 without), 1-10 %
// more triangles; at 0.05 within 1.08 but up to 5 times the triangles where the footprint is tight
// (zoom 3, ratio 4). Not next to a polygon: its ring has kinks no split resolves (along the
// ridges of the distance to it), and splits at its corners made degenerate triangles (the model
// sweep's setups).
constexpr double kSlopeTolerance = 0.075;

// How far, in cells, lenses whose footprint the image border cuts may move before their mesh is
// made anew (moved_mesh): the deformed mesh's picture drifts from a fresh mesh's as the border
// bends the ring anew (test DraggedAlongTheBorder: within 0.25 px of a 4x finer solve at 1.5
// cells, like a fresh mesh; 0.41 at 2 cells, 1.6 at 3).
constexpr double kMovedMeshDrift = 1.5;

// A zoom is short of the one asked when it is at least 0.1 % less (the fit warning's threshold)
// or, in the search, short by more than rounding.
constexpr double kShortfall = 1e-3, kRounding = 1e-9;
bool short_of(double fit, double zoom, double by) { return fit < zoom * (1 - by); }

// How much finer than the mesh option's the grid may be made for small circles (grid_vertices):
// at most 4 times the vertices.
constexpr int kFinestGrid = 2;

// The fit's search: rounds (a group lowered may split into groups that share room differently)
// of largest_fitting_log_zoom's halvings of the group's log zoom.
constexpr int kFitRounds = 3;
// The most times the solved box grows to hold the footprints on its own mesh (solved_box).
constexpr int kBoxRounds = 4;

// Whether lenses `to` are lenses `from` moved, all by one translation: the same shapes, zooms
// and footprints (only circles and polygons are compared; other regions are never the same).
bool moved_only(const std::vector<Lens>& from, const std::vector<Lens>& to) {
  if (from.empty() || from.size() != to.size()) return false;
  const Eigen::Vector2d shift = to[0].region.peak() - from[0].region.peak();
  const double tolerance = 1e-9 * (1 + shift.norm());
  auto moved = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (b - a - shift).norm() <= tolerance * (1 + a.norm());
  };
  for (size_t k = 0; k < from.size(); ++k) {
    const Lens &a = from[k], &b = to[k];
    if (a.zoom != b.zoom || a.footprint != b.footprint || a.profile != b.profile) return false;
    const std::optional<Circle> ca = a.region.circle(), cb = b.region.circle();
    const auto pa = a.region.outline(), pb = b.region.outline();
    if (ca && cb) {
      if (ca->radius != cb->radius || !moved(ca->center, cb->center)) return false;
    } else if (pa && pb && pa->size() == pb->size()) {
      for (size_t i = 0; i < pa->size(); ++i)
        if (!moved((*pa)[i], (*pb)[i])) return false;
    } else {
      return false;
    }
  }
  return true;
}

// A lens magnified with others (one focus group) is solved at the group's
// zoom, the largest of theirs (focus_groups): that is the zoom it gets and the one reported, and
// where it is at least the one asked no reason is given (a lens asked 3 beside one asked 4 was
// told it got 2.6 of 3, limited by a side, where it was shown at 3.3).
void report_group_zooms(const std::vector<Lens>& asked, const std::vector<Lens>& solved,
                        double width, double height, FittedLenses& fit) {
  for (const FocusGroup& group : focus_groups(solved, width, height, FitMesh{})) {
    double zoom = 1;  // exp(group.log_zoom), exactly the zoom of a lens alone
    for (size_t k : group.lenses) zoom = std::max(zoom, solved[k].zoom);
    for (size_t k : group.lenses) {
      fit.zoom_fits[k] = zoom;
      if (!short_of(fit.zoom_fits[k], asked[k].zoom, kShortfall)) fit.zoom_fit_reasons[k].clear();
    }
  }
}

}  // namespace

// Every footprint lies within its group's reach plus margin of the group's centre.
Eigen::AlignedBox2d FocusPipeline::solved_box(const std::vector<Lens>& lenses) const {
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(c_.width, c_.height));
  if (lenses.empty()) return image;
  auto holding = [&](Eigen::AlignedBox2d box, const FitMesh& mesh) {
    for (const FocusGroup& g : focus_groups(lenses, c_.width, c_.height, mesh)) {
      const Eigen::Vector2d half = Eigen::Vector2d::Constant(g.disk_radius());
      box.extend(g.centre - half).extend(g.centre + half);
    }
    return box.intersection(image);
  };
  // The footprints as the regions' own extents give them, then as the mesh of the box holds
  // them (a lens near a side may be magnified about the side's point on it, its footprint
  // larger: polygons of 10 and 15 px beside sides, whose footprints reached beyond the box, were
  // magnified 1.56 where solved at 1.64), until the box holds them on its own mesh.
  Eigen::AlignedBox2d box = holding(Eigen::AlignedBox2d(), FitMesh{});
  for (int round = 0; round < kBoxRounds; ++round) {
    const double cell = cell_size(box, lenses);
    const Eigen::AlignedBox2d grown = holding(box, {cell, focus_band(lenses, cell)});
    if (grown.min() == box.min() && grown.max() == box.max()) break;
    box = grown;
  }
  return box;
}

int FocusPipeline::grid_vertices(const Eigen::AlignedBox2d& box,
                                 const std::vector<Lens>& lenses) const {
  // A circle of under 2 cells is not followed by the mesh, and its band of 1.4 cells holds its
  // footprint's edge too close to fit any zoom: an r 15 circle at zoom 3 beside an r 200 one 780
  // px away on a 1024 px image (10 px cells) was not magnified at all, though alone it got 3.
  // A circle too small even for the finest grid leaves the grid as it is (its cost would buy
  // nothing: the 1000 random setups' sweep took 55 s with it, 42 s without).
  const double side = box.sizes().maxCoeff();
  // In a stretched frame, the cell the image's box would have: the mesh as fine across the
  // stretch as without it (a 400 x 20 strip at zoom 2 fitted 1.85 on the frame's coarser cells,
  // 1.93 in the image), and finer along it.
  const double image_side = box.sizes().cwiseQuotient(stretch_).maxCoeff();
  const int mesh = int(std::ceil((c_.options.mesh - 1) * side / image_side - 1e-9)) + 1;
  int vertices = mesh;
  for (const Lens& lens : lenses) {
    if (!lens.region.circle()) continue;
    const double cells = std::ceil(2 * side / lens.region.size() * (1 + 1e-9));
    if (cells <= kFinestGrid * (mesh - 1)) vertices = std::max(vertices, int(cells) + 1);
  }
  return vertices;
}

double FocusPipeline::cell_size(const Eigen::AlignedBox2d& box,
                                const std::vector<Lens>& lenses) const {
  return box.sizes().maxCoeff() / (grid_vertices(box, lenses) - 1);
}

BaseMesh FocusPipeline::base_mesh(const std::vector<Lens>& lenses, Eigen::AlignedBox2d& box,
                                  bool draft, std::vector<int>* on_curve) const {
  box = solved_box(lenses);
  Grid patch = make_grid(box.sizes().x(), box.sizes().y(), grid_vertices(box, lenses));
  patch.V.rowwise() += box.min().transpose();
  const double cell = cell_size(box, lenses);
  if (!meshed_along_regions(lenses, cell)) {
    if (on_curve) on_curve->assign(size_t(patch.V.rows()), -1);
    return BaseMesh(patch);
  }
  // Vertices on every region's boundary and footprint's edge, so no triangle crosses them, and
  // smaller triangles where the start bends.
  const double band = focus_band(lenses, cell);
  MeshRefinement refine;
  if (!draft && c_.options.mesh_tolerance > 0) {
    refine.map = focus_map(lenses, focus_groups(lenses, c_.width, c_.height, {cell, band}), cell,
                           band, c_.width, c_.height, *c_.pool);
    // No coarser than kRelativeTolerance of the smallest region's reach either: the start's
    // shape across a triangle is off by about its position error over its size, so a small
    // lens needs a finer tolerance for the same shape (a 20 px circle at zoom 3, footprint
    // ratio 12: shape max 0.995 at 0.2 px, 0.850 at 0.05 px, the radial bound 0.792).
    refine.tolerance = c_.options.mesh_tolerance;
    refine.slope_tolerance = kSlopeTolerance;
    for (const Lens& lens : lenses)
      refine.tolerance = std::min(refine.tolerance, kRelativeTolerance * lens.region.reach());
  }
  BaseMesh mesh(patch);
  static_cast<PlanarMesh&>(mesh) =
      conform_mesh(patch, focus_curves(lenses, cell, band, c_.width, c_.height), 0.4 * patch.cell,
                   refine, on_curve);
  return mesh;
}

// footprint_clear_of_border, on the mesh the lenses are solved on.
bool FocusPipeline::clear_of_border(const std::vector<Lens>& lenses,
                                    const Eigen::AlignedBox2d& box) const {
  const double cell = cell_size(box, lenses);
  const std::vector<FocusGroup> groups =
      focus_groups(lenses, c_.width, c_.height, {cell, focus_band(lenses, cell)});
  return std::all_of(groups.begin(), groups.end(), [&](const FocusGroup& g) {
    return footprint_clear_of_border(g, c_.width, c_.height);
  });
}

// The last frame's mesh (`memo`) for `lenses`, the memo's moved by one translation, over their
// solved `box`; none where it must be made anew. Where every footprint is clear of the border,
// now and where the mesh was made, the lenses' map is the memo's translated, and so is the mesh.
// Else the border bends the map differently where the lenses now are: the mesh deforms with them
// (moved_focus_mesh), and is made anew once they have drifted kMovedMeshDrift cells from where it
// was made.
std::optional<BaseMesh> FocusPipeline::moved_mesh(const MeshMemo& memo,
                                                  const std::vector<Lens>& lenses,
                                                  Eigen::AlignedBox2d& box) const {
  box = solved_box(lenses);
  BaseMesh mesh = memo.mesh;
  if (memo.clear && clear_of_border(lenses, box)) {
    mesh.V.rowwise() += (box.min() - memo.box.min()).transpose();
    return mesh;
  }
  const double cell = cell_size(box, lenses);
  const double shift = (lenses[0].region.peak() - memo.lenses[0].region.peak()).norm();
  if (memo.drift + shift > kMovedMeshDrift * cell) return std::nullopt;
  std::optional<Eigen::MatrixX2d> V = moved_focus_mesh(
      memo.mesh, memo.on_curve, memo.lenses, memo.box, cell_size(memo.box, memo.lenses), lenses,
      box, cell, c_.width, c_.height, *c_.pool);
  if (!V) return std::nullopt;
  mesh.V = std::move(*V);
  return mesh;
}

std::vector<Lens> FocusPipeline::fitting(const std::vector<Lens>& lenses,
                                         std::vector<std::string>& reasons, bool merge) const {
  const double width = c_.width, height = c_.height;
  // The fits of lenses at their zooms, on the box and mesh cell they would be solved on; the
  // footprint of a lens that has no ratio of its own follows its zoom (footprint_ratio).
  auto fits_of = [&](const std::vector<Lens>& at, std::vector<std::string>* why,
                     const std::vector<size_t>* only = nullptr) {
    const double cell = cell_size(solved_box(at), at);
    return fitting_zooms(at, cell, focus_band(at, cell), width, height, why, only, stretch_);
  };
  // Lenses near each other first share the room between them (or are magnified as one where
  // that gives both more), each set fitted on the mesh cell of the box it would be solved on
  // alone; then each group is lowered until it fits where it is, on the box of them all.
  std::vector<int> neighbours;
  std::vector<Lens> out = shared_room_zooms(
      lenses,
      [&](const std::vector<Lens>& at) {
        const double cell = cell_size(solved_box(at), at);
        return FitMesh{cell, focus_band(lenses, cell)};
      },
      width, height, merge, &neighbours);
  const std::vector<Lens> shared = out;
  for (int round = 0; round < kFitRounds; ++round) {
    // Every group that does not fit is lowered with the others as they were (not one after the
    // other: the first would leave the room it gave up to the next, two lenses alike got 4.26
    // and 4.39).
    const std::vector<double> fits = fits_of(out, nullptr);
    std::vector<Lens> lowered = out;
    bool fit = true;
    for (const FocusGroup& group : focus_groups(out, width, height, FitMesh{})) {
      auto members_fit = [&](const std::vector<Lens>& at, const std::vector<double>& f) {
        return std::none_of(group.lenses.begin(), group.lenses.end(),
                            [&](size_t k) { return short_of(f[k], at[k].zoom, kRounding); });
      };
      if (members_fit(out, fits)) continue;
      fit = false;
      // The largest group log zoom below the one that does not fit at which the group fits, each
      // member's log zoom scaled with it (0 is the identity).
      std::vector<Lens> trial = out;
      auto scale = [&](double log_zoom) {
        for (size_t k : group.lenses)
          trial[k].zoom = std::exp(log_zoom / group.log_zoom * std::log(out[k].zoom));
      };
      scale(largest_fitting_log_zoom(group.log_zoom, [&](double log_zoom) {
        scale(log_zoom);
        return members_fit(trial, fits_of(trial, nullptr, &group.lenses));
      }));
      for (size_t k : group.lenses) lowered[k].zoom = trial[k].zoom;
    }
    out = std::move(lowered);
    if (fit) break;
  }
  // What limits each lens that gets less than asked: the fit just above its zoom.
  reasons.assign(out.size(), "");
  std::vector<Lens> above = out;
  bool short_any = false;
  for (size_t k = 0; k < out.size(); ++k) {
    if (!short_of(out[k].zoom, lenses[k].zoom, kShortfall)) continue;
    above[k].zoom = std::min(lenses[k].zoom, out[k].zoom * (1 + kShortfall));
    short_any = true;
  }
  if (!short_any) return out;
  fits_of(above, &reasons);
  for (size_t k = 0; k < out.size(); ++k) {
    if (!short_of(out[k].zoom, lenses[k].zoom, kShortfall))
      reasons[k].clear();
    else if (neighbours[k] >= 0 && !short_of(out[k].zoom, shared[k].zoom, kShortfall))
      // Held where the room shared with a neighbour ends (a zoom just above would group them;
      // the fit may lower it by a rounding more: a lens r 150 asked 4 beside one asked 2, 900
      // px apart, lowered by 2e-6, was told the side the two would have as one).
      reasons[k] = beside_reason(size_t(neighbours[k]));
  }
  return out;
}

FittedLenses FocusPipeline::unfitted(const std::vector<Lens>& lenses) const {
  for (const Lens& lens : lenses) validate_lens(lens, c_.width, c_.height);
  FittedLenses fit;
  fit.lenses = lenses;
  fit.mesh = base_mesh(lenses, fit.box, false, nullptr);
  return fit;
}

FittedLenses FocusPipeline::fitted(const std::vector<Lens>& lenses, SolveCache* cache,
                                   bool draft) const {
  for (const Lens& lens : lenses) validate_lens(lens, c_.width, c_.height);
  // Thin regions, solved in a frame stretched across them.
  const Eigen::Vector2d stretch = frame_stretch(lenses);
  if (stretch == Eigen::Vector2d::Ones()) return fitted_here(lenses, cache, draft);
  auto frame = std::make_shared<const FocusPipeline>(
      LensContext{c_.width * stretch.x(), c_.height * stretch.y(), c_.options, Grid{}, c_.pool},
      stretch);
  FittedLenses fit = frame->fitted_here(stretched(lenses, stretch), cache, draft);
  fit.frame = std::move(frame);
  fit.stretch = stretch;
  return fit;
}

FittedLenses FocusPipeline::fitted_here(const std::vector<Lens>& lenses, SolveCache* cache,
                                        bool draft) const {
  MeshMemo* memo = cache ? &cache->mesh : nullptr;
  bool merged = false;
  FittedLenses fit = fitted_once(lenses, true, memo, draft, &merged);
  // Lenses magnified as one whose ring their mesh does not hold (two circles with a gap between
  // them beside a side: 1.13 where they fit 1.80 apart) are solved apart where that gives the
  // lens that gets least more.
  if (!fit.mesh_limited || !merged) return fit;
  MeshMemo apart_memo;
  FittedLenses apart = fitted_once(lenses, false, memo ? &apart_memo : nullptr, draft);
  auto least = [](const std::vector<double>& zooms) {
    return *std::min_element(zooms.begin(), zooms.end());
  };
  if (!(least(apart.zoom_fits) > least(fit.zoom_fits))) return fit;
  if (memo) *memo = std::move(apart_memo);
  return apart;
}

FittedLenses FocusPipeline::fitted_once(const std::vector<Lens>& lenses, bool merge, MeshMemo* memo,
                                        bool draft, bool* merged) const {
  FittedLenses fit;
  std::vector<Lens>& out = fit.lenses;
  out = fitting(lenses, fit.zoom_fit_reasons, merge);
  if (merged) {
    const std::vector<FocusGroup> groups = focus_groups(out, c_.width, c_.height, FitMesh{});
    *merged = std::any_of(groups.begin(), groups.end(),
                          [](const FocusGroup& g) { return g.lenses.size() > 1; });
  }
  std::vector<double>& fits = fit.zoom_fits;
  for (const Lens& lens : out) fits.push_back(lens.zoom);
  // A circle too small for the grid to follow, even at its finest (grid_vertices), got less for
  // it: a finer mesh fits more, and a draft is solved on a finer grid (LensSession), so that a
  // drag does not show it unmagnified where the frame at rest magnifies it.
  // (The grid's cell only where a circle got less: a drag's frames need not find the groups again.)
  std::optional<double> grid_cell;
  for (size_t k = 0; k < out.size(); ++k) {
    if (!lenses[k].region.circle() || !short_of(fits[k], lenses[k].zoom, kShortfall)) continue;
    if (!grid_cell) grid_cell = cell_size(solved_box(out), out);
    if (lenses[k].region.size() >= 2 * *grid_cell) continue;
    fit.mesh_limited = true;
    fit.zoom_fit_reasons[k] = "the mesh (a finer mesh fits more)";
  }
  // Then what the mesh of the fitted lenses, the one they are solved on, holds without folding
  // (its footprints kept, the curves the mesh follows); the last frame's mesh, moved, where the
  // lenses only moved. Last, the zooms each group is solved at are the ones reported.
  auto lower = [&](const std::vector<double>& caps) {
    for (size_t k = 0; k < out.size(); ++k) {
      if (!short_of(caps[k], out[k].zoom, kRounding)) continue;
      fit.mesh_limited = true;
      out[k].footprint = footprint_ratio(out[k]);
      out[k].zoom = fits[k] = std::max(1.0, caps[k]);
      if (short_of(fits[k], lenses[k].zoom, kShortfall))
        fit.zoom_fit_reasons[k] = "the mesh (a finer mesh fits more)";
    }
    report_group_zooms(lenses, out, c_.width, c_.height, fit);
  };
  if (memo && moved_only(memo->lenses, out)) {
    if (std::optional<BaseMesh> moved = moved_mesh(*memo, out, fit.box)) {
      fit.mesh = std::move(*moved);
      memo->drift += (out[0].region.peak() - memo->lenses[0].region.peak()).norm();
      memo->lenses = out;
      memo->box = fit.box;
      memo->mesh = fit.mesh;
      lower(memo->unfolding);
      return fit;
    }
  }
  std::vector<int> on_curve;
  fit.mesh = base_mesh(out, fit.box, draft, &on_curve);
  const double cell = cell_size(fit.box, out);
  const std::vector<double> unfolding =
      unfolding_zooms(fit.mesh, out, cell, focus_band(out, cell), c_.width, c_.height, *c_.pool);
  if (memo)
    *memo = MeshMemo{
        out, fit.box, fit.mesh, unfolding, std::move(on_curve), clear_of_border(out, fit.box)};
  lower(unfolding);
  // Lowered, a lens leaves a neighbour more room, whose footprint may then reach beyond the box
  // (a blend's, FocusGroup::blend, moved the box's side): it is meshed again.
  if (fit.mesh_limited && !fit.box.contains(solved_box(out)))
    fit.mesh = base_mesh(out, fit.box, draft, nullptr);
  return fit;
}

LensResult FocusPipeline::solve_once(const Eigen::AlignedBox2d& box,
                                     const std::vector<Lens>& lenses, const PlanarMesh& mesh,
                                     const std::vector<double>& h, SolveCache& cache,
                                     const SolveControl& control, int solve) const {
  const auto start = Clock::now();
  LensResult r;
  r.model = LensModel::kFocus;
  r.focus_log_zooms = h;
  r.mesh = mesh;
  r.box = box;
  // The focus field read as a lift (for --export-mesh): z = log zoom times the solved area's long
  // side.
  const double cell = cell_size(box, lenses);
  const double band = focus_band(lenses, cell);
  FocusField focus = focus_field(r.mesh.V, lenses, h, cell, band, c_.width, c_.height, *c_.pool);
  Lifted lifted;
  lifted.V.resize(r.mesh.V.rows(), 3);
  lifted.V.leftCols<2>() = r.mesh.V;
  lifted.V.col(2) = focus.log_scale * box.sizes().maxCoeff();
  lifted.level = focus.level;
  lifted.log_zoom = focus.log_scale;
  lifted.inside.resize(size_t(r.mesh.V.rows()));
  for (size_t i = 0; i < lifted.inside.size(); ++i)
    lifted.inside[i] = focus.constraints.focus[i] >= 0;
  r.timings.lift = ms_since(start);
  // The texture is the mesh itself: the focus magnifies the planar region.
  const auto t = Clock::now();
  r.warp.source = r.mesh.V;
  r.timings.texture = ms_since(t);

  // The footprints' box: its sides inside the image are pinned (focus_field), those on the
  // image border slide.
  FlattenOptions options = c_.options.flatten;
  options.boundary = Boundary::kSliding;
  options.standard = Standard::kScaled;
  options.weights = FlattenWeights::kCotan;
  prepare_flattener(lifted, focus.constraints, options, r, cache);

  // The start is the focus lens's own (its ring), better than any prediction.
  const auto flatten = [&](const SolveControl& progress) {
    return flatten_focus(*cache.flattener, r.mesh, lenses, focus, cell, band, c_.width, c_.height,
                         *c_.pool, &progress);
  };
  flatten_and_finish(flatten, lenses, lifted, options.boundary, control, solve, start, cache, r);
  return r;
}

}  // namespace geolens
