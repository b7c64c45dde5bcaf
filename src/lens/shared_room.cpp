#include "lens/shared_room.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include "lens/focus_lens.h"

namespace geolens {

namespace {

// largest_fitting_log_zoom's points: kSamples of [0, ln kMaxZoom], then halvings of one (to
// 2^-20 of ln 8 in all: 0.0002 %).
constexpr int kSamples = 16, kHalvings = 16;

// A set of lenses magnified as one focus group, and where it fits alone.
struct Unit {
  std::vector<size_t> lenses;  // sorted
  double asked = 0;            // the largest log zoom asked of its lenses
  double cap = 0;              // the log zoom it fits alone, at most `asked`
  Eigen::Vector2d centre;      // its group's centre, pixels
  double reach = 0;            // its group's reach plus the focus band, pixels
};

// The log zoom level L up to which the rings of units a and b fit side by side, each at the
// least of L and its cap c: r_a e^(min(c_a, L) / 0.8) + r_b e^(min(c_b, L) / 0.8) <= |centre_a -
// centre_b|, growing in L; infinite where both fit at their caps, 0 where not even the identity.
double shared_level(const Unit& a, const Unit& b) {
  const double apart = (a.centre - b.centre).norm();
  auto overlap = [&](double level) {
    return a.reach + ring_need(a.reach, std::min(a.cap, level)) + b.reach +
           ring_need(b.reach, std::min(b.cap, level)) - apart;
  };
  double lo = 0, hi = std::max(a.cap, b.cap);
  if (overlap(hi) <= 0) return std::numeric_limits<double>::infinity();
  if (overlap(lo) >= 0) return 0;
  for (int i = 0; i < 60; ++i) (overlap(0.5 * (lo + hi)) <= 0 ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// A pair of units whose rings meet: their shared level and their indices (i < j).
using Conflict = std::tuple<double, size_t, size_t>;

// shared_room_zooms's work: the lenses grouped into units, which merge while that gives both
// lenses of a pair at least as much as apart, each unit's cap found once.
class SharedRoom {
 public:
  SharedRoom(const std::vector<Lens>& lenses, const FitMeshOf& mesh_of, double width, double height)
      : lenses_(lenses), mesh_of_(mesh_of), width_(width), height_(height) {}

  // Groups the lenses into units: each lens its own, then (with `merge`) the pair in most
  // conflict that fits together merged, until none does; leaves each unit's level.
  void group(bool merge);
  // The lenses at the zooms their units get; `neighbours` as shared_room_zooms's.
  std::vector<Lens> zooms(std::vector<int>* neighbours);

 private:
  // The lenses of `members`, each at log zoom L.
  std::vector<Lens> at(const std::vector<size_t>& members, double log_zoom) const;
  // The unit of `members` with its cap, found the first time it is asked for.
  const Unit& unit_of(const std::vector<size_t>& members);
  // Whether the rings of some lens of units a and b meet, each lens at its own log zoom or at
  // `log_zoom` if given, each region held `band` wider (focus_groups's test with band 0).
  bool rings_meet(const std::vector<size_t>& a, const std::vector<size_t>& b, double band,
                  std::optional<double> log_zoom = std::nullopt) const;
  // The level unit u gets apart: the least of its cap and its pairs' level.
  double apart(size_t u) { return std::min(unit_of(units_[u]).cap, level_[u]); }
  // Each unit's level (and the lens that set it) from the pairs whose rings meet with `band`,
  // and those pairs, least level first.
  std::vector<Conflict> conflicts(double band);
  // Merges the first of `conflicts` whose merged unit fits at least as well as both apart;
  // whether one was.
  bool merge_first(const std::vector<Conflict>& conflicts);

  const std::vector<Lens>& lenses_;
  const FitMeshOf& mesh_of_;
  const double width_, height_;
  std::map<std::vector<size_t>, Unit> known_;  // units whose cap was found
  std::vector<std::vector<size_t>> units_;
  // Per unit, the least level of its pairs: it gets the least of that and its cap.
  std::vector<double> level_;
  std::vector<int> by_;  // per unit, a lens of the unit that set its level
};

std::vector<Lens> SharedRoom::at(const std::vector<size_t>& members, double log_zoom) const {
  std::vector<Lens> out;
  for (size_t k : members) {
    out.push_back(lenses_[k]);
    out.back().zoom = std::exp(log_zoom);
  }
  return out;
}

const Unit& SharedRoom::unit_of(const std::vector<size_t>& members) {
  auto found = known_.find(members);
  if (found != known_.end()) return found->second;
  Unit u;
  u.lenses = members;
  for (size_t k : members) u.asked = std::max(u.asked, std::log(lenses_[k].zoom));
  auto fits = [&](double log_zoom) {
    const std::vector<Lens> group = at(members, log_zoom);
    const FitMesh mesh = mesh_of_(group);
    const double fit = group_fitting_zoom(focus_group_of(group, width_, height_, mesh), group,
                                          mesh.cell, mesh.band, width_, height_);
    return fit >= std::exp(log_zoom) * (1 - 1e-9);
  };
  u.cap = fits(u.asked) ? u.asked : largest_fitting_log_zoom(u.asked, fits);
  const std::vector<Lens> group = at(members, u.cap);
  const FitMesh mesh = mesh_of_(group);
  const FocusGroup g = focus_group_of(group, width_, height_, mesh);
  u.centre = g.centre;
  u.reach = g.reach + mesh.band;
  return known_.emplace(members, std::move(u)).first->second;
}

bool SharedRoom::rings_meet(const std::vector<size_t>& a, const std::vector<size_t>& b, double band,
                            std::optional<double> log_zoom) const {
  auto ringed = [&](size_t k) {
    const double reach = lenses_[k].region.reach() + band;
    return reach + ring_need(reach, log_zoom.value_or(std::log(lenses_[k].zoom)));
  };
  for (size_t i : a)
    for (size_t j : b)
      if ((lenses_[i].region.peak() - lenses_[j].region.peak()).norm() < ringed(i) + ringed(j))
        return true;
  return false;
}

std::vector<Conflict> SharedRoom::conflicts(double band) {
  level_.assign(units_.size(), std::numeric_limits<double>::infinity());
  by_.assign(units_.size(), -1);
  std::vector<Conflict> conflicts;
  for (size_t i = 0; i < units_.size(); ++i)
    for (size_t j = i + 1; j < units_.size(); ++j) {
      if (!rings_meet(units_[i], units_[j], band)) continue;
      const double l = shared_level(unit_of(units_[i]), unit_of(units_[j]));
      if (std::isinf(l)) continue;
      if (l < level_[i]) level_[i] = l, by_[i] = int(units_[j].front());
      if (l < level_[j]) level_[j] = l, by_[j] = int(units_[i].front());
      conflicts.emplace_back(l, i, j);
    }
  std::sort(conflicts.begin(), conflicts.end());
  return conflicts;
}

bool SharedRoom::merge_first(const std::vector<Conflict>& conflicts) {
  for (const auto& [l, i, j] : conflicts) {
    std::vector<size_t> both = units_[i];
    both.insert(both.end(), units_[j].begin(), units_[j].end());
    std::sort(both.begin(), both.end());
    const Unit& m = unit_of(both);
    if (m.cap < std::max(apart(i), apart(j))) continue;
    // focus_groups must group them at the merged zoom.
    if (!rings_meet(units_[i], units_[j], 0, m.cap)) continue;
    units_[i] = std::move(both);
    units_.erase(units_.begin() + std::ptrdiff_t(j));
    return true;
  }
  return false;
}

void SharedRoom::group(bool merge) {
  // Only units whose rings could meet at the zooms asked, with the band of the coarsest mesh
  // (all lenses'), need their caps.
  const double band = mesh_of_(lenses_).band;
  for (size_t k = 0; k < lenses_.size(); ++k) units_.push_back({k});
  // The levels of the units as they are; then the pair in most conflict that fits together
  // merged, if any, and again.
  for (;;) {
    const std::vector<Conflict> pairs = conflicts(band);
    if (!merge || !merge_first(pairs)) break;
  }
}

std::vector<Lens> SharedRoom::zooms(std::vector<int>* neighbours) {
  std::vector<Lens> out = lenses_;
  for (size_t u = 0; u < units_.size(); ++u) {
    if (!known_.count(units_[u])) continue;  // near no other: as asked, the fit lowers it
    for (size_t k : units_[u]) {
      out[k].zoom = std::exp(apart(u));
      if (neighbours && level_[u] < unit_of(units_[u]).cap) (*neighbours)[k] = by_[u];
    }
  }
  return out;
}

}  // namespace

double largest_fitting_log_zoom(double below, const std::function<bool(double)>& fits) {
  // `fits` may fail near 0 too (a region below three cells of a coarse mesh keeps two cells of
  // its footprint for the mesh, which a footprint of twice a zoom near 1 does not hold): the
  // largest of kSamples points that fits first, then halvings above it.
  const double top = std::log(kMaxZoom), step = top / kSamples;
  int k = int(std::ceil(below / step)) - 1;
  while (k > 0 && !fits(k * step)) --k;
  if (k <= 0) k = 0;
  double lo = k * step, hi = (k + 1) * step;
  for (int i = 0; i < kHalvings; ++i) {
    const double mid = 0.5 * (lo + hi);
    (mid < below && fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

std::string beside_reason(size_t neighbour) {
  return "lens " + std::to_string(neighbour + 1) + " beside it (lenses farther apart fit more)";
}

std::vector<Lens> shared_room_zooms(const std::vector<Lens>& lenses, const FitMeshOf& mesh_of,
                                    double width, double height, bool merge,
                                    std::vector<int>* neighbours) {
  const size_t n = lenses.size();
  if (neighbours) neighbours->assign(n, -1);
  if (n < 2) return lenses;  // a lens alone (a drag's every frame) shares nothing
  SharedRoom room(lenses, mesh_of, width, height);
  room.group(merge);
  return room.zooms(neighbours);
}

}  // namespace geolens
