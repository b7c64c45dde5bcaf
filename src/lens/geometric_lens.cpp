#include "geolens/lens/geometric_lens.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "core/thread_pool.h"
#include "geolens/core/errors.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/measure/distortion.h"
#include "lens/calibration.h"
#include "lens/focus_lens.h"
#include "lens/framing.h"
#include "lens/shared_room.h"
#include "lens/solve_cache.h"

namespace geolens {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The side of a grid cell over `box` with `mesh` vertices along its long side, pixels.
double cell_size(const Eigen::AlignedBox2d& box, int mesh) {
  return box.sizes().maxCoeff() / (mesh - 1);
}

// The refinement's tolerance relative to a region's reach (base_grid).
constexpr double kRelativeTolerance = 1.0 / 400;

}  // namespace

Extent parse_extent(const std::string& name) {
  if (name == "global") return Extent::kGlobal;
  if (name == "local") return Extent::kLocal;
  throw InvalidInput("parse_extent: unknown extent '" + name + "' (expected global or local)");
}

std::string to_string(Extent extent) { return extent == Extent::kGlobal ? "global" : "local"; }

LensModel parse_lens_model(const std::string& name) {
  if (name == "focus") return LensModel::kFocus;
  if (name == "lift") return LensModel::kLift;
  if (name == "field") return LensModel::kField;
  if (name == "auto") return LensModel::kAuto;
  throw InvalidInput("parse_lens_model: unknown lens model '" + name +
                     "' (expected focus, lift, field or auto)");
}

std::string to_string(LensModel model) {
  switch (model) {
    case LensModel::kFocus:
      return "focus";
    case LensModel::kLift:
      return "lift";
    case LensModel::kField:
      return "field";
    case LensModel::kAuto:
      return "auto";
  }
  return "?";
}

std::vector<std::string> zoom_warnings(const std::vector<Lens>& lenses, const LensResult& result) {
  // Six significant digits, as the CLI has always printed these zooms (3.20563).
  auto text = [](double value) { return (std::ostringstream() << value).str(); };
  std::vector<std::string> lines;
  for (size_t k = 0; k < lenses.size(); ++k) {
    const std::string lens = "lens " + std::to_string(k + 1);
    if (k < result.zoom_fit_reasons.size() && !result.zoom_fit_reasons[k].empty())
      lines.push_back(lens + " gets zoom " + text(result.zoom_fits[k]) + " of the " +
                      text(lenses[k].zoom) + " asked where it is, limited by " +
                      result.zoom_fit_reasons[k]);
    else if (k < result.zoom_measured.size() &&
             std::abs(result.zoom_measured[k] / lenses[k].zoom - 1) > 0.1)
      lines.push_back(lens + " reached zoom " + text(result.zoom_measured[k]) + " of the " +
                      text(lenses[k].zoom) + " requested");
  }
  return lines;
}

void validate(const LensOptions& o) {
  require_option(std::isfinite(o.extent_factor) && o.extent_factor > 1 && o.extent_factor <= 100,
                 "validate", "extent_factor",
                 "must be in (1, 100], got " + number_text(o.extent_factor));
  require_mesh_vertices(o.mesh, "validate");
  if (o.draft_mesh != 0) require_mesh_vertices(o.draft_mesh, "validate", "draft_mesh");
  // Finer than a hundredth of a pixel shows nothing and refines without end (1e-9 ran away).
  require_option(
      std::isfinite(o.mesh_tolerance) && (o.mesh_tolerance == 0 || o.mesh_tolerance >= 0.01),
      "validate", "mesh_tolerance",
      "must be 0 (no refinement) or at least 0.01 pixels, got " + number_text(o.mesh_tolerance));
  require(std::isfinite(o.zoom_tolerance) && o.zoom_tolerance > 0, "validate",
          "zoom tolerance must be positive");
  require(o.max_calibration_solves >= 1, "validate", "at least one calibration solve needed");
  validate(o.subdivision);
  validate(o.flatten);
}

GeometricLens::GeometricLens(double width, double height, const LensOptions& options)
    : width_(width), height_(height), options_(options) {
  validate(options);
  grid_ = make_grid(width, height, options.mesh);
  pool_ = std::make_shared<ThreadPool>(options.flatten.threads);
}

// The area solved: the image, or a local patch around the lenses (kFocus: their footprints).
Eigen::AlignedBox2d GeometricLens::solved_box(const std::vector<Lens>& lenses) const {
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  const bool focus = model_for(lenses) == LensModel::kFocus;
  if ((options_.extent == Extent::kGlobal && !focus) || lenses.empty()) return image;
  Eigen::AlignedBox2d box;
  if (focus) {
    // Every footprint lies within its group's reach plus margin of the group's centre.
    for (const FocusGroup& g : focus_groups(lenses, width_, height_)) {
      const Eigen::Vector2d half = Eigen::Vector2d::Constant(g.reach + g.margin);
      box.extend(g.centre - half).extend(g.centre + half);
    }
    return box.intersection(image);
  }
  for (const Lens& lens : lenses) {
    const Eigen::Vector2d centre = lens.region.bounds().center();
    const Eigen::Vector2d half = 0.5 * lens.region.bounds().sizes().array() +
                                 (options_.extent_factor - 1) * lens.region.size();
    box.extend(centre - half).extend(centre + half);
  }
  return box.intersection(image);
}

// The grid the lift is built on: the image's, or one over the solved box whose border carries
// the sides flags so the flattening pins it; for focus lenses on circles and polygons, made to
// follow every region's boundary and footprint's edge and, unless a draft, refined where the
// start bends.
Grid GeometricLens::base_grid(const std::vector<Lens>& lenses, Eigen::AlignedBox2d& box, bool draft,
                              std::vector<int>* on_curve) const {
  box = solved_box(lenses);
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  if (box.isApprox(image) && model_for(lenses) != LensModel::kFocus) return grid_;
  Grid patch = make_grid(box.sizes().x(), box.sizes().y(), options_.mesh);
  patch.V.rowwise() += box.min().transpose();
  const double cell = cell_size(box, options_.mesh);
  if (model_for(lenses) == LensModel::kFocus && meshed_along_regions(lenses, cell)) {
    // Vertices on every region's boundary and footprint's edge, so no triangle crosses them,
    // and smaller triangles where the start bends.
    const double band = focus_band(lenses, cell);
    MeshRefinement refine;
    if (!draft && options_.mesh_tolerance > 0) {
      refine.map = focus_map(lenses, focus_groups(lenses, width_, height_), cell, band, width_,
                             height_, *pool_);
      // No coarser than kRelativeTolerance of the smallest region's reach either: the start's
      // shape across a triangle is off by about its position error over its size, so a small
      // lens needs a finer tolerance for the same shape (a 20 px circle at zoom 3, footprint
      // ratio 12: shape max 0.995 at 0.2 px, 0.850 at 0.05 px, the radial bound 0.792).
      refine.tolerance = options_.mesh_tolerance;
      for (const Lens& lens : lenses)
        refine.tolerance = std::min(refine.tolerance, kRelativeTolerance * lens.region.reach());
    }
    static_cast<PlanarMesh&>(patch) =
        conform_mesh(patch, focus_curves(lenses, cell, band, width_, height_), 0.4 * patch.cell,
                     refine, on_curve);
  } else if (on_curve) {
    on_curve->assign(size_t(patch.V.rows()), -1);
  }
  return patch;
}

LensModel resolved_model(LensModel model, const std::vector<Lens>& lenses) {
  if (model != LensModel::kAuto) return model;
  for (const Lens& lens : lenses)
    if (!lens.region.circle()) return LensModel::kField;
  return LensModel::kLift;
}

LensModel GeometricLens::model_for(const std::vector<Lens>& lenses) const {
  return resolved_model(options_.model, lenses);
}

namespace {

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

}  // namespace

// How far, in cells, lenses whose footprint the image border cuts may move before their mesh is
// made anew (moved_grid): the deformed mesh's picture drifts from a fresh mesh's as the border
// bends the ring anew (test DraggedAlongTheBorder: within 0.25 px of a 4x finer solve at 1.5
// cells, like a fresh mesh; 0.41 at 2 cells, 1.6 at 3).
constexpr double kMovedMeshDrift = 1.5;

// Whether every focus group's footprint is clear of the image border (footprint_clear_of_border).
bool GeometricLens::clear_of_border(const std::vector<Lens>& lenses) const {
  const std::vector<FocusGroup> groups = focus_groups(lenses, width_, height_);
  return std::all_of(groups.begin(), groups.end(), [&](const FocusGroup& g) {
    return footprint_clear_of_border(g, width_, height_);
  });
}

// The last frame's mesh (`memo`) for `lenses`, the memo's moved by one translation, over their
// solved `box`; none where it must be made anew. Where every footprint is clear of the border,
// now and where the mesh was made, the lenses' map is the memo's translated, and so is the mesh.
// Else the border bends the map differently where the lenses now are: the mesh deforms with them
// (moved_focus_mesh), and is made anew once they have drifted kMovedMeshDrift cells from where it
// was made.
std::optional<Grid> GeometricLens::moved_grid(const MeshMemo& memo, const std::vector<Lens>& lenses,
                                              Eigen::AlignedBox2d& box) const {
  box = solved_box(lenses);
  Grid grid = memo.grid;
  if (memo.clear && clear_of_border(lenses)) {
    grid.V.rowwise() += (box.min() - memo.box.min()).transpose();
    return grid;
  }
  const double cell = cell_size(box, options_.mesh);
  const double shift = (lenses[0].region.peak() - memo.lenses[0].region.peak()).norm();
  if (memo.drift + shift > kMovedMeshDrift * cell) return std::nullopt;
  std::optional<Eigen::MatrixX2d> V = moved_focus_mesh(memo.grid, memo.on_curve, memo.lenses,
                                                       memo.box, cell_size(memo.box, options_.mesh),
                                                       lenses, box, cell, width_, height_, *pool_);
  if (!V) return std::nullopt;
  grid.V = std::move(*V);
  return grid;
}

namespace {

// A zoom is short of the one asked when it is at least 0.1 % less (the fit warning's threshold)
// or, in the search, short by more than rounding.
constexpr double kShortfall = 1e-3, kRounding = 1e-9;
bool short_of(double fit, double zoom, double by) { return fit < zoom * (1 - by); }

// The fit's search: rounds (a group lowered may split into groups that share room differently)
// of largest_fitting_log_zoom's halvings of the group's log zoom.
constexpr int kFitRounds = 3;

// A lens magnified with others (one focus group) is solved at the group's
// zoom, the largest of theirs (focus_groups): that is the zoom it gets and the one reported, and
// where it is at least the one asked no reason is given (a lens asked 3 beside one asked 4 was
// told it got 2.6 of 3, limited by a side, where it was shown at 3.3).
void report_group_zooms(const std::vector<Lens>& asked, const std::vector<Lens>& solved,
                        double width, double height, LensResult& r) {
  for (const FocusGroup& group : focus_groups(solved, width, height)) {
    double zoom = 1;  // exp(group.log_zoom), exactly the zoom of a lens alone
    for (size_t k : group.lenses) zoom = std::max(zoom, solved[k].zoom);
    for (size_t k : group.lenses) {
      r.zoom_fits[k] = zoom;
      if (!short_of(r.zoom_fits[k], asked[k].zoom, kShortfall)) r.zoom_fit_reasons[k].clear();
    }
  }
}

}  // namespace

std::vector<Lens> GeometricLens::fitting(const std::vector<Lens>& lenses,
                                         std::vector<std::string>& reasons, bool merge) const {
  // The fits of lenses at their zooms, on the box and mesh cell they would be solved on; the
  // footprint of a lens that has no ratio of its own follows its zoom (footprint_ratio).
  auto fits_of = [&](const std::vector<Lens>& at, std::vector<std::string>* why,
                     const std::vector<size_t>* only = nullptr) {
    const Eigen::AlignedBox2d box = solved_box(at);
    const double cell = cell_size(box, options_.mesh);
    return fitting_zooms(at, cell, focus_band(at, cell), width_, height_, why, only);
  };
  // Lenses near each other first share the room between them (or are magnified as one where
  // that gives both more), each set fitted on the mesh cell of the box it would be solved on
  // alone; then each group is lowered until it fits where it is, on the box of them all.
  std::vector<int> neighbours;
  std::vector<Lens> out = shared_room_zooms(
      lenses,
      [&](const std::vector<Lens>& at) {
        const double cell = cell_size(solved_box(at), options_.mesh);
        return FitMesh{cell, focus_band(lenses, cell)};
      },
      width_, height_, merge, &neighbours);
  const std::vector<Lens> shared = out;
  for (int round = 0; round < kFitRounds; ++round) {
    // Every group that does not fit is lowered with the others as they were (not one after the
    // other: the first would leave the room it gave up to the next, two lenses alike got 4.26
    // and 4.39).
    const std::vector<double> fits = fits_of(out, nullptr);
    std::vector<Lens> lowered = out;
    bool fit = true;
    for (const FocusGroup& group : focus_groups(out, width_, height_)) {
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
    else if (neighbours[k] >= 0 && out[k].zoom == shared[k].zoom)
      // Held where the room shared with a neighbour ends (a zoom just above would group them).
      reasons[k] = beside_reason(size_t(neighbours[k]));
  }
  return out;
}

std::vector<Lens> GeometricLens::fitted(const std::vector<Lens>& lenses, LensResult& r, Grid& grid,
                                        Eigen::AlignedBox2d& box, SolveCache* cache,
                                        bool draft) const {
  r.zoom_fits.clear();
  r.zoom_fit_reasons.clear();
  r.mesh_limited = false;
  for (const Lens& lens : lenses) validate_lens(lens, width_, height_);
  if (model_for(lenses) != LensModel::kFocus) {
    grid = base_grid(lenses, box);
    return lenses;
  }
  MeshMemo* memo = cache ? &cache->mesh : nullptr;
  bool merged = false;
  std::vector<Lens> out = fitted_focus(lenses, true, r, grid, box, memo, draft, &merged);
  // Lenses magnified as one whose ring their mesh does not hold (two circles with a gap between
  // them beside a side: 1.13 where they fit 1.80 apart) are solved apart where that gives the
  // lens that gets least more.
  if (!r.mesh_limited || !merged) return out;
  LensResult apart_r;
  Grid apart_grid;
  Eigen::AlignedBox2d apart_box;
  MeshMemo apart_memo;
  std::vector<Lens> apart = fitted_focus(lenses, false, apart_r, apart_grid, apart_box,
                                         memo ? &apart_memo : nullptr, draft);
  auto least = [](const std::vector<double>& zooms) {
    return *std::min_element(zooms.begin(), zooms.end());
  };
  if (!(least(apart_r.zoom_fits) > least(r.zoom_fits))) return out;
  r.zoom_fits = std::move(apart_r.zoom_fits);
  r.zoom_fit_reasons = std::move(apart_r.zoom_fit_reasons);
  r.mesh_limited = apart_r.mesh_limited;
  grid = std::move(apart_grid);
  box = apart_box;
  if (memo) *memo = std::move(apart_memo);
  return apart;
}

std::vector<Lens> GeometricLens::fitted_focus(const std::vector<Lens>& lenses, bool merge,
                                              LensResult& r, Grid& grid, Eigen::AlignedBox2d& box,
                                              MeshMemo* memo, bool draft, bool* merged) const {
  std::vector<Lens> out = fitting(lenses, r.zoom_fit_reasons, merge);
  if (merged) {
    const std::vector<FocusGroup> groups = focus_groups(out, width_, height_);
    *merged = std::any_of(groups.begin(), groups.end(),
                          [](const FocusGroup& g) { return g.lenses.size() > 1; });
  }
  std::vector<double>& fits = r.zoom_fits;
  for (const Lens& lens : out) fits.push_back(lens.zoom);
  // Then what the mesh of the fitted lenses, the one they are solved on, holds without folding
  // (its footprints kept, the curves the mesh follows); the last frame's mesh, moved, where the
  // lenses only moved. Last, the zooms each group is solved at are the ones reported.
  auto lower = [&](const std::vector<double>& caps) {
    for (size_t k = 0; k < out.size(); ++k) {
      if (!short_of(caps[k], out[k].zoom, kRounding)) continue;
      r.mesh_limited = true;
      out[k].footprint = footprint_ratio(out[k]);
      out[k].zoom = fits[k] = std::max(1.0, caps[k]);
      if (short_of(fits[k], lenses[k].zoom, kShortfall))
        r.zoom_fit_reasons[k] = "the mesh (a finer mesh fits more)";
    }
    report_group_zooms(lenses, out, width_, height_, r);
  };
  if (memo && moved_only(memo->lenses, out)) {
    if (std::optional<Grid> moved = moved_grid(*memo, out, box)) {
      grid = std::move(*moved);
      memo->drift += (out[0].region.peak() - memo->lenses[0].region.peak()).norm();
      memo->lenses = out;
      memo->box = box;
      memo->grid = grid;
      lower(memo->unfolding);
      return out;
    }
  }
  std::vector<int> on_curve;
  grid = base_grid(out, box, draft, &on_curve);
  const double out_cell = cell_size(box, options_.mesh);
  const std::vector<double> unfolding =
      unfolding_zooms(grid, out, out_cell, focus_band(out, out_cell), width_, height_, *pool_);
  if (memo) *memo = MeshMemo{out, box, grid, unfolding, std::move(on_curve), clear_of_border(out)};
  lower(unfolding);
  return out;
}

FlattenOptions GeometricLens::flatten_options(LensModel model) const {
  FlattenOptions o = options_.flatten;
  if (model == LensModel::kFocus) {
    // The footprints' box: its sides inside the image are pinned (focus_field), those on the
    // image border slide.
    o.boundary = Boundary::kSliding;
    o.standard = Standard::kScaled;
    o.weights = FlattenWeights::kCotan;
    return o;
  }
  if (options_.extent == Extent::kLocal) o.boundary = Boundary::kFixed;
  if (model == LensModel::kField) {
    // The rest areas already weigh the magnified triangles; the paper's (1 + h) A weights on
    // top made the focus so stiff that the context folded into a band one triangle wide.
    o.standard = Standard::kScaled;
    o.weights = FlattenWeights::kCotan;
  }
  return o;
}

// Lifts `mesh` (covering `box`) and maps the texture onto it, filling r's heights, mesh, box,
// source coordinates and the lift and texture timings (from `start`).
Lifted GeometricLens::lift_and_texture(const std::vector<Lens>& lenses,
                                       const std::vector<double>& heights, const PlanarMesh& mesh,
                                       const Eigen::AlignedBox2d& box, Clock::time_point start,
                                       LensResult& r, FocusField& focus) const {
  r.model = model_for(lenses);
  r.heights = heights;
  r.mesh = mesh;
  r.box = box;
  Lifted lifted;
  if (r.model == LensModel::kFocus) {
    // The focus field read as a lift (for --export-mesh): z = log zoom times the solved area's
    // long side.
    const double cell = cell_size(box, options_.mesh);
    focus = focus_field(r.mesh.V, lenses, heights, cell, focus_band(lenses, cell), width_, height_,
                        *pool_);
    lifted.V.resize(r.mesh.V.rows(), 3);
    lifted.V.leftCols<2>() = r.mesh.V;
    lifted.V.col(2) = focus.log_scale * box.sizes().maxCoeff();
    lifted.level = focus.level;
    lifted.log_zoom = focus.log_scale;
    lifted.inside.resize(size_t(r.mesh.V.rows()));
    for (size_t i = 0; i < lifted.inside.size(); ++i)
      lifted.inside[i] = focus.constraints.focus[i] >= 0;
  } else {
    lifted = lift(r.mesh.V, lenses, heights);
  }
  r.timings.lift = ms_since(start);
  const auto t = Clock::now();
  texture(lifted, r);
  r.timings.texture = ms_since(t);
  return lifted;
}

// Texture coordinates of the lifted mesh, with the fold fallback; the field model keeps them.
void GeometricLens::texture(const Lifted& lifted, LensResult& r) const {
  if (r.model == LensModel::kField || r.model == LensModel::kFocus) {
    r.warp.source = r.mesh.V;
    return;
  }
  std::vector<char> fixed(lifted.inside.size());
  for (size_t i = 0; i < fixed.size(); ++i) fixed[i] = !lifted.inside[i] || r.mesh.sides[i] != 0;
  r.warp.source = harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, options_.texture);
  if (options_.texture == TextureWeights::kCotan && count_folds(r.warp.source, r.mesh.F) > 0) {
    // Negative cotan weights folded the map (steep walls): redo it with non-negative weights.
    r.warp.source =
        harmonic_texture(lifted.V, r.mesh.F, fixed, r.mesh.V, TextureWeights::kPositiveCotan);
    r.texture_fallback = true;
  }
}

// After the flattening: the framed WarpMesh and the zoom measured at each lens's peak.
void GeometricLens::finish(const std::vector<Lens>& lenses, const Lifted& lifted,
                           LensResult& r) const {
  r.lifted = lifted.V;
  r.flat = r.flattening.X;
  r.warp.F = r.mesh.F;
  r.warp.screen = frame(r.flat, flatten_options(r.model).boundary, width_, height_);
  r.warp.screen_width = int(std::lround(width_));
  r.warp.screen_height = int(std::lround(height_));
  const Eigen::AlignedBox2d image(Eigen::Vector2d::Zero(), Eigen::Vector2d(width_, height_));
  if (!r.box.isApprox(image)) add_identity_frame(r.warp, r.mesh, r.box, width_, height_);
  for (const Lens& lens : lenses) {
    const double radius =
        zoom_measure_radius(lens.region.size(), r.box.sizes().maxCoeff(), options_.mesh);
    r.zoom_measured.push_back(magnification_at(r.warp, lens.region.peak(), radius));
    r.zoom_parameter.push_back(lens.zoom);
  }
  r.solves = 1;
}

PlanarMesh GeometricLens::solved_mesh(const Grid& grid, const std::vector<Lens>& lenses,
                                      const std::vector<double>& heights) const {
  if (model_for(lenses) == LensModel::kFocus) return grid;
  return subdivide(
      grid, [&](const Eigen::Vector2d& p) { return lift_height(lenses, heights, p); },
      options_.subdivision);
}

LensResult GeometricLens::solve_with_heights(const std::vector<Lens>& lenses,
                                             const std::vector<double>& heights) const {
  for (const Lens& lens : lenses) validate_lens(lens, width_, height_);
  Eigen::AlignedBox2d box;
  const Grid grid = base_grid(lenses, box);
  SolveCache cache;
  return solve_once(solved_mesh(grid, lenses, heights), box, lenses, heights, cache, {}, 1);
}

LensResult GeometricLens::solve_once(const PlanarMesh& mesh, const Eigen::AlignedBox2d& box,
                                     const std::vector<Lens>& lenses,
                                     const std::vector<double>& heights, SolveCache& cache,
                                     const SolveControl& control, int solve) const {
  const auto start = Clock::now();
  LensResult r;
  FocusField focus;
  const Lifted lifted = lift_and_texture(lenses, heights, mesh, box, start, r, focus);

  auto t = Clock::now();
  // A local patch has the same topology wherever it is, as long as its size is unchanged; a
  // focus lens's also needs the same pinned vertices.
  const bool same_topology = cache.flattener && cache.model == r.model &&
                             cache.flat.rows() == r.mesh.V.rows() &&
                             (cache.box.sizes() - r.box.sizes()).norm() < 1e-9 &&
                             focus.constraints.pinned == cache.pinned &&
                             cache.faces.rows() == r.mesh.F.rows() && cache.faces == r.mesh.F;
  if (same_topology) {
    cache.flattener->reweight(lifted.V, lifted.level, lifted.log_zoom, focus.constraints);
    const Eigen::RowVector2d shift = (r.box.min() - cache.box.min()).transpose();
    cache.flat.rowwise() += shift;
    if (cache.predicted.rows() == cache.flat.rows()) cache.predicted.rowwise() += shift;
  } else {
    cache.flattener = std::make_unique<Flattener>(lifted.V, r.mesh.F, lifted.level, r.mesh.sides,
                                                  flatten_options(r.model), lifted.log_zoom,
                                                  focus.constraints, pool_);
    cache.flat = r.mesh.V;
    cache.predicted.resize(0, 2);
  }
  cache.box = r.box;
  cache.pinned = std::move(focus.constraints.pinned);
  cache.faces = r.mesh.F;
  cache.model = r.model;
  r.timings.factorize = ms_since(t);

  t = Clock::now();
  // The progress of this calibration solve, numbered.
  SolveControl numbered{control.cancel, nullptr};
  if (control.progress)
    numbered.progress = [&](const SolveProgress& p) {
      control.progress({solve, p.iteration, p.energy});
    };
  // A lens dragged steadily moves its flattening steadily: a prediction is the better start
  // (unless it folds a triangle; after a stop or a jump it costs at most an iteration). A focus
  // lens has a better one still: its power-law start.
  const bool predicted = cache.predicted.rows() == cache.flat.rows();
  if (r.model == LensModel::kFocus) {
    const double cell = cell_size(box, options_.mesh);
    r.flattening = flatten_focus(*cache.flattener, r.mesh, lenses, focus, cell,
                                 focus_band(lenses, cell), width_, height_, *pool_, &numbered);
  } else {
    r.flattening =
        cache.flattener->solve(cache.flat, predicted ? &cache.predicted : nullptr, &numbered);
  }
  cache.predicted.resize(0, 2);  // only the first solve has one
  cache.flat = r.flattening.X;
  r.timings.iterate = ms_since(t);

  finish(lenses, lifted, r);
  r.timings.total = ms_since(start);
  return r;
}

LensResult GeometricLens::calibrated(const std::vector<Lens>& lenses, const PlanarMesh& mesh,
                                     const Eigen::AlignedBox2d& box,
                                     const std::vector<double>& heights, SolveCache& cache,
                                     const SolveControl& control) const {
  return calibrate(lenses, model_for(lenses), heights, options_.zoom_tolerance,
                   options_.max_calibration_solves, [&](const std::vector<double>& h, int solve) {
                     return solve_once(mesh, box, lenses, h, cache, control, solve);
                   });
}

LensResult GeometricLens::solve(const std::vector<Lens>& asked, const SolveControl& control) const {
  LensResult fit;
  Grid grid;
  Eigen::AlignedBox2d box;
  const std::vector<Lens> lenses = fitted(asked, fit, grid, box);
  std::vector<double> h;
  const LensModel model = model_for(lenses);
  for (const Lens& lens : lenses)
    h.push_back(lens.zoom == 1 ? 0.0 : initial_height(lens, model, grid.cell));
  SolveCache cache;
  LensResult r = calibrated(lenses, solved_mesh(grid, lenses, h), box, h, cache, control);
  r.zoom_fits = std::move(fit.zoom_fits);
  r.zoom_fit_reasons = std::move(fit.zoom_fit_reasons);
  r.mesh_limited = fit.mesh_limited;
  return r;
}

}  // namespace geolens
