#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "eval/fixed_text.h"
#include "eval/lens_json.h"
#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"

namespace geolens {

namespace {

nlohmann::json zone_json(const ZoneStatistics& zone) {
  if (zone.triangles == 0) return {{"mean", nullptr}, {"max", nullptr}};
  return {{"mean", zone.conformal_mean}, {"max", zone.conformal_max}};
}

std::string zone_cell(const ZoneStatistics& zone) {
  if (zone.triangles == 0) return "—";
  return fixed_text(zone.conformal_mean, 3) + " / " + fixed_text(zone.conformal_max, 3);
}

std::string area_cell(const ZoneStatistics& zone) {
  return zone.triangles == 0 ? "—" : fixed_text(zone.area_distortion_mean, 3);
}

// The largest focus uniformity over the lenses, each over the region given (measure_foci): the
// one definition every table and the stats use.
double focus_uniformity(const ComparedMethod& m) {
  double u = 0;
  for (const FocusMeasure& f : m.foci) u = std::max(u, f.uniformity);
  return u;
}

}  // namespace

std::string comparison_json(const Comparison& c) {
  nlohmann::json report = {{"methods", nlohmann::json::array()}};
  for (const ComparedMethod& m : c.methods) {
    const RegionStatistics& r = m.regions;
    nlohmann::json lenses = nlohmann::json::array();
    for (size_t k = 0; k < c.lenses.size(); ++k)
      lenses.push_back(lens_json(c.lenses[k], m.zoom_measured[k], m.foci[k], c.geometric.model));
    report["methods"].push_back({{"name", m.name},
                                 {"zoom_center", m.zoom_measured.front()},
                                 {"focus_uniformity", focus_uniformity(m)},
                                 {"distortion",
                                  {{"focus", zone_json(r.focus)},
                                   {"transition", zone_json(r.transition)},
                                   {"context", zone_json(r.context)},
                                   {"overall", zone_json(r.overall)}}},
                                 {"occluded_percent", r.occluded_percent},
                                 {"flipped", r.overall.flipped},
                                 {"lenses", lenses}});
  }
  return report.dump(2) + "\n";
}

std::string comparison_markdown(const Comparison& c, const std::string& title) {
  std::ostringstream md;
  md << "# geolens compare: " << title << "\n\n";
  for (size_t k = 0; k < c.targets.size(); ++k) {
    const CircleLens& target = c.targets[k];
    const Region& region = c.lenses[k].region;
    md << "Lens " << k + 1 << ": "
       << (region.circle() ? "disk" : "a " + region.kind() + "; its disk") << " at ("
       << fixed_text(target.center.x(), 1) << ", " << fixed_text(target.center.y(), 1)
       << "), radius " << fixed_text(target.radius, 1) << " px, zoom requested "
       << fixed_text(c.lenses[k].zoom, 3) << ", measured on the geometric lens "
       << fixed_text(target.zoom, 3)
       << "; every classic lens is matched to that zoom (same measure) and radius"
       << (region.circle() ? ".\n"
                           : ": radial, the classic lenses magnify the disk about the region's "
                             "peak that holds it (radius " +
                                 fixed_text(region.reach(), 1) + " px), not the region's shape.\n");
  }
  md << "\nShape distortion is s1/s2 - 1 of each triangle's source -> screen Jacobian (0 = shape "
        "kept), mean (weighted by source area) / max per region. Regions by source position: "
        "focus = within a r / zoom of the centre (what a flat-top lens of the same radius and "
        "zoom shows at full zoom on the inner fraction a of its disk), transition = the rest of "
        "the lens disk, "
        "context = outside. Zoom at centre = magnification_at the first lens's centre. Focus "
        "uniformity = max / min magnification over the region a lens was given (the largest "
        "over the lenses), as in the per-lens table below and in --stats. Occluded = source area "
        "not shown, percent of the image. — = no triangle in that region.\n\n";
  md << "| method | zoom at centre | focus uniformity | focus | transition | context | overall "
        "| occluded % | flipped |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const ComparedMethod& m : c.methods) {
    const RegionStatistics& r = m.regions;
    md << "| " << m.name << " | " << fixed_text(m.zoom_measured.front(), 3) << " | "
       << fixed_text(focus_uniformity(m), 3) << " | " << zone_cell(r.focus) << " | "
       << zone_cell(r.transition) << " | " << zone_cell(r.context) << " | " << zone_cell(r.overall)
       << " | " << fixed_text(r.occluded_percent, 2) << " | " << r.overall.flipped << " |\n";
  }
  md << "\nArea distortion, mean of max(a, 1/a) - 1 with a = s1 s2 the area scale (0 = area "
        "kept; the focus is magnified on purpose, so it is large there):\n\n";
  md << "| method | focus | transition | context |\n|---|---:|---:|---:|\n";
  for (const ComparedMethod& m : c.methods) {
    md << "| " << m.name << " | " << area_cell(m.regions.focus) << " | "
       << area_cell(m.regions.transition) << " | " << area_cell(m.regions.context) << " |\n";
  }
  md << "\nPer lens, over the region given (comparison.h): zoom = mean magnification, "
        "uniformity = max / min, shape distortion mean / max, footprint = radius of the disk of "
        "the same area as the source disturbed by more than 5 %, moved = the largest displacement "
        "beyond the footprint (px):\n\n";
  md << "| method | lens | zoom | uniformity | shape | footprint | moved |\n"
        "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const ComparedMethod& m : c.methods) {
    for (size_t k = 0; k < m.foci.size(); ++k) {
      const FocusMeasure& f = m.foci[k];
      md << "| " << m.name << " | " << k + 1 << " | " << fixed_text(f.zoom, 3) << " | "
         << fixed_text(f.uniformity, 3) << " | " << fixed_text(f.shape_mean, 3) << " / "
         << fixed_text(f.shape_max, 3) << " | " << fixed_text(f.footprint_radius, 0) << " | "
         << fixed_text(f.displacement_beyond_footprint, 1) << " |\n";
    }
  }
  const double image_area = double(c.width) * c.height;
  md << "\nGeometric lens, the paper's Eq. 7 energy of its flattening (cot weights, measured from "
        "rigid): "
     << fixed_text(c.eq7_energy, 1) << " px^2, " << fixed_text(c.eq7_energy / image_area, 5)
     << " per source pixel.\n";
  return md.str();
}

std::string sweep_json(const Sweep& sweep) {
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < sweep.ratios.size(); ++i) {
    for (const SweepPoint& p : sweep.points) {
      if (p.ratio != sweep.ratios[i]) continue;
      rows.push_back({{"method", p.method},
                      {"ratio", p.ratio},
                      {"zoom", p.zoom},
                      {"uniformity", p.uniformity},
                      {"shape_max", p.shape_max},
                      {"footprint_radius", p.footprint_radius},
                      {"bound", sweep.bound[i]},
                      {"rim_bound", sweep.rim_bound[i]}});
    }
  }
  return nlohmann::json({{"points", rows}}).dump(2) + "\n";
}

std::string sweep_markdown(const Sweep& sweep, const std::string& title) {
  std::ostringstream md;
  md << "# geolens compare --sweep: " << title << "\n\n"
     << "Largest shape distortion s1/s2 - 1 of each method against the footprint ratio F (the "
        "focus lens's `--footprint`; every classic lens has radius F r and a flat top of the "
        "region's size), the focus uniformity (max / min magnification over the region) in "
        "brackets where it is above 1.01, the radial bound 1 / (1 - ln zoom / ln F) - 1 at "
        "the zoom the focus lens reached, and the bound of the focus lens's ring, whose rim "
        "ends without a crease (rim_distortion_bound, at most 1.3 times the radial bound).\n\n"
        "| F | zoom | bound | rim bound |";
  std::vector<std::string> methods;
  for (const SweepPoint& p : sweep.points)
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end())
      methods.push_back(p.method);
  for (const std::string& m : methods) md << " " << m << " |";
  md << "\n|---:|---:|---:|---:|";
  for (size_t m = 0; m < methods.size(); ++m) md << "---:|";
  md << "\n";
  for (size_t i = 0; i < sweep.ratios.size(); ++i) {
    const SweepPoint* geometric = nullptr;
    for (const SweepPoint& p : sweep.points)
      if (p.ratio == sweep.ratios[i] && p.method == "geometric") geometric = &p;
    require(geometric != nullptr, "sweep_markdown",
            "no geometric point at ratio " + std::to_string(sweep.ratios[i]));
    md << "| " << fixed_text(sweep.ratios[i], 2) << " | " << fixed_text(geometric->zoom, 3) << " | "
       << fixed_text(sweep.bound[i], 3) << " | " << fixed_text(sweep.rim_bound[i], 3) << " |";
    for (const SweepPoint& p : sweep.points) {
      if (p.ratio != sweep.ratios[i]) continue;
      md << " " << fixed_text(p.shape_max, 3)
         << (p.uniformity > 1.01 ? " (" + fixed_text(p.uniformity, 2) + ")" : "") << " |";
    }
    md << "\n";
  }
  return md.str();
}

}  // namespace geolens
