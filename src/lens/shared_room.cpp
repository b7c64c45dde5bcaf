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
  // The lenses of `members`, each at log zoom L.
  auto at = [&](const std::vector<size_t>& members, double log_zoom) {
    std::vector<Lens> out;
    for (size_t k : members) {
      out.push_back(lenses[k]);
      out.back().zoom = std::exp(log_zoom);
    }
    return out;
  };
  std::map<std::vector<size_t>, Unit> known;  // units whose cap was found
  auto unit_of = [&](const std::vector<size_t>& members) -> const Unit& {
    auto found = known.find(members);
    if (found != known.end()) return found->second;
    Unit u;
    u.lenses = members;
    for (size_t k : members) u.asked = std::max(u.asked, std::log(lenses[k].zoom));
    auto fits = [&](double log_zoom) {
      const std::vector<Lens> group = at(members, log_zoom);
      const FitMesh mesh = mesh_of(group);
      const double fit = group_fitting_zoom(focus_group_of(group, width, height), group, mesh.cell,
                                            mesh.band, width, height);
      return fit >= std::exp(log_zoom) * (1 - 1e-9);
    };
    u.cap = fits(u.asked) ? u.asked : largest_fitting_log_zoom(u.asked, fits);
    const std::vector<Lens> group = at(members, u.cap);
    const FocusGroup g = focus_group_of(group, width, height);
    u.centre = g.centre;
    u.reach = g.reach + mesh_of(group).band;
    return known.emplace(members, std::move(u)).first->second;
  };
  // Whether the rings of some lens of units a and b meet, each lens at its own log zoom or at
  // `log_zoom` if given, each region held `band` wider (focus_groups's test with band 0).
  auto rings_meet = [&](const std::vector<size_t>& a, const std::vector<size_t>& b, double band,
                        std::optional<double> log_zoom = std::nullopt) {
    auto ringed = [&](size_t k) {
      const double reach = lenses[k].region.reach() + band;
      return reach + ring_need(reach, log_zoom.value_or(std::log(lenses[k].zoom)));
    };
    for (size_t i : a)
      for (size_t j : b)
        if ((lenses[i].region.peak() - lenses[j].region.peak()).norm() < ringed(i) + ringed(j))
          return true;
    return false;
  };
  // Only units whose rings could meet at the zooms asked, with the band of the coarsest mesh
  // (all lenses'), need their caps.
  const double band = mesh_of(lenses).band;
  std::vector<std::vector<size_t>> units;
  for (size_t k = 0; k < n; ++k) units.push_back({k});
  // Per unit, the least level of its pairs: it gets the least of that and its cap.
  std::vector<double> level;
  std::vector<int> by;  // per unit, a lens of the unit that set its level
  auto apart = [&](size_t u) { return std::min(unit_of(units[u]).cap, level[u]); };
  for (;;) {
    level.assign(units.size(), std::numeric_limits<double>::infinity());
    by.assign(units.size(), -1);
    std::vector<std::tuple<double, size_t, size_t>> conflicts;
    for (size_t i = 0; i < units.size(); ++i)
      for (size_t j = i + 1; j < units.size(); ++j) {
        if (!rings_meet(units[i], units[j], band)) continue;
        const double l = shared_level(unit_of(units[i]), unit_of(units[j]));
        if (std::isinf(l)) continue;
        if (l < level[i]) level[i] = l, by[i] = int(units[j].front());
        if (l < level[j]) level[j] = l, by[j] = int(units[i].front());
        conflicts.emplace_back(l, i, j);
      }
    std::sort(conflicts.begin(), conflicts.end());
    bool merged = false;
    for (const auto& [l, i, j] : conflicts) {
      if (!merge) break;
      std::vector<size_t> both = units[i];
      both.insert(both.end(), units[j].begin(), units[j].end());
      std::sort(both.begin(), both.end());
      const Unit& m = unit_of(both);
      if (m.cap < std::max(apart(i), apart(j))) continue;
      // focus_groups must group them at the merged zoom.
      if (!rings_meet(units[i], units[j], 0, m.cap)) continue;
      units[i] = std::move(both);
      units.erase(units.begin() + std::ptrdiff_t(j));
      merged = true;
      break;
    }
    if (!merged) break;
  }
  std::vector<Lens> out = lenses;
  for (size_t u = 0; u < units.size(); ++u) {
    if (!known.count(units[u])) continue;  // near no other: as asked, the fit lowers it
    for (size_t k : units[u]) {
      out[k].zoom = std::exp(apart(u));
      if (neighbours && level[u] < unit_of(units[u]).cap) (*neighbours)[k] = by[u];
    }
  }
  return out;
}

}  // namespace geolens
