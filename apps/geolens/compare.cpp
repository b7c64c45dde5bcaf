#include "compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/eval/focus_measure.h"
#include "geolens/eval/footprint_sweep.h"
#include "geolens/io/file_io.h"
#include "geolens/io/image.h"
#include "geolens/io/run_files.h"
#include "geolens/lens/classic_lens.h"
#include "geolens/lens/focus_lens.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/measure/distortion_regions.h"
#include "geolens/render/annotate.h"
#include "geolens/render/heatmap.h"
#include "geolens/render/render.h"

namespace geolens {

namespace {

namespace fs = std::filesystem;

struct Method {
  std::string name;
  WarpMesh warp;
  double zoom_center = 0;  // magnification_at the first lens's centre
  TriangleDistortion measures;
  RegionStatistics regions;
  std::vector<FocusMeasure> foci;  // per lens, over the region the user gave
};

// The radius of the classic lenses matched to `lens` (and of the disk its regions are measured
// in): its footprint for a focus lens, else its region's size.
double classic_radius(const Lens& lens, const LensOptions& options) {
  return options.model == LensModel::kFocus ? footprint_ratio(lens) * lens.region.reach()
                                            : lens.region.size();
}

// The classic lens matched to `lens` at `zoom`: for a focus lens its flat top shows the region at
// full zoom (focus fraction zoom / footprint ratio), else the default fraction.
CircleLens classic_target(const Lens& lens, const LensOptions& options, double zoom) {
  CircleLens target{lens.region.peak(), classic_radius(lens, options), zoom};
  if (options.model == LensModel::kFocus)
    target.focus_fraction = std::min(0.95, zoom / footprint_ratio(lens));
  return target;
}

nlohmann::json foci_json(const std::vector<FocusMeasure>& foci) {
  nlohmann::json list = nlohmann::json::array();
  for (const FocusMeasure& f : foci)
    list.push_back({{"zoom", f.zoom},
                    {"uniformity", f.uniformity},
                    {"shape_mean", f.shape_mean},
                    {"shape_max", f.shape_max},
                    {"footprint_radius", f.footprint_radius},
                    {"displacement_beyond_footprint", f.displacement_beyond_footprint}});
  return list;
}

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// `warp` with its screen translated and scaled so that the square window at `origin` with side
// `side` (screen pixels) fills a tile x tile picture.
WarpMesh framed(const WarpMesh& warp, const Eigen::Vector2d& origin, double side, int tile) {
  WarpMesh out = warp;
  out.screen = (warp.screen.rowwise() - origin.transpose()) * (tile / side);
  out.screen_width = out.screen_height = tile;
  return out;
}

// Input, then every method: a cell each (four label lines, the output, its heatmap), four cells
// per row, the colour scale below. Every picture shows the same square around the lenses.
Image make_panel(const Image& source, const MipPyramid& pyramid, const std::vector<Method>& methods,
                 const std::vector<CircleLens>& lenses, double heat_max, int tile) {
  Eigen::AlignedBox2d box;
  for (const CircleLens& lens : lenses) {
    box.extend(lens.center - Eigen::Vector2d::Constant(lens.radius));
    box.extend(lens.center + Eigen::Vector2d::Constant(lens.radius));
  }
  const double side = 1.3 * box.sizes().maxCoeff();
  const Eigen::Vector2d origin = box.center() - Eigen::Vector2d::Constant(side / 2);
  // Labels at twice the font size when the longest method name (158 pixels) fits the tile.
  const int scale = tile >= 176 ? 2 : 1, line = 11 * scale, gap = 6;
  const int label_height = 4 * line + gap, cell_width = tile + gap,
            cell_height = label_height + 2 * tile + gap + 2 * gap;
  const int columns = 4, rows = int(methods.size() + 1 + columns - 1) / columns;
  Image panel(columns * cell_width + gap, rows * cell_height + gap, 3, 255);
  RenderOptions options;
  options.width = options.height = tile;
  const std::array<uint8_t, 3> ink = {20, 20, 20};

  const WarpMesh identity = identity_warp(source.width, source.height);
  Image input = to_rgb(render(framed(identity, origin, side, tile), pyramid, options));
  std::vector<Region> circles;
  for (const CircleLens& lens : lenses) circles.push_back(Region::circle(lens.center, lens.radius));
  outline_regions(input, circles, origin, tile / side, tile / side);

  for (size_t cell = 0; cell <= methods.size(); ++cell) {
    const int left = gap + int(cell % columns) * cell_width;
    const int top = gap + int(cell / columns) * cell_height;
    if (cell == 0) {
      draw_text(panel, left, top, "input", scale, ink);
      draw_text(panel, left, top + line, "lens outlined", scale, ink);
      paste(panel, input, left, top + label_height);
      // The notes go where the heatmap is in the other cells, in the largest font that fits.
      const char* notes[] = {"top: output",  "below: shape", "distortion",    "s1/s2 - 1",
                             "focus: inner", "half of lens", "hides: % image"};
      const int count = int(std::size(notes));
      const int note_scale = count * (11 * scale + 2) <= tile ? scale : 1;
      if (count * (11 * note_scale + 2) > tile) continue;
      int y = top + label_height + tile + gap;
      for (const char* note : notes) {
        draw_text(panel, left, y, note, note_scale, ink);
        y += 11 * note_scale + 2;
      }
      continue;
    }
    const Method& m = methods[cell - 1];
    draw_text(panel, left, top, m.name, scale, ink);
    draw_text(panel, left, top + line, "zoom " + fixed(m.zoom_center, 2), scale, ink);
    draw_text(panel, left, top + 2 * line, "max " + fixed(m.regions.overall.conformal_max, 2),
              scale, ink);
    std::string notes;
    if (m.regions.occluded_percent >= 0.05)
      notes = "hides " + fixed(m.regions.occluded_percent, 1) + "%";
    if (m.regions.overall.flipped > 0)
      notes += (notes.empty() ? "" : ", ") + std::to_string(m.regions.overall.flipped) + " flipped";
    draw_text(panel, left, top + 3 * line, notes, scale, ink);
    const WarpMesh warp = framed(m.warp, origin, side, tile);
    const Image image = to_rgb(render(warp, pyramid, options));
    paste(panel, image, left, top + label_height);
    paste(panel, heatmap(warp, m.measures.conformal, m.measures.flipped, image, heat_max), left,
          top + label_height + tile + gap);
  }
  return with_legend(panel, heat_max, "shape distortion s1/s2 - 1");
}

nlohmann::json zone_json(const ZoneStatistics& zone) {
  if (zone.triangles == 0) return {{"mean", nullptr}, {"max", nullptr}};
  return {{"mean", zone.conformal_mean}, {"max", zone.conformal_max}};
}

std::string zone_cell(const ZoneStatistics& zone) {
  if (zone.triangles == 0) return "—";
  return fixed(zone.conformal_mean, 3) + " / " + fixed(zone.conformal_max, 3);
}

std::string area_cell(const ZoneStatistics& zone) {
  return zone.triangles == 0 ? "—" : fixed(zone.area_distortion_mean, 3);
}

std::string report_markdown(const CompareArgs& args, const std::vector<CircleLens>& lenses,
                            const std::vector<double>& zoom_requested,
                            const std::vector<Method>& methods, double eq7_total,
                            double image_area) {
  std::ostringstream md;
  md << "# geolens compare: " << fs::path(args.input).filename().string() << "\n\n";
  for (size_t k = 0; k < lenses.size(); ++k) {
    md << "Lens " << k + 1 << ": disk at (" << fixed(lenses[k].center.x(), 1) << ", "
       << fixed(lenses[k].center.y(), 1) << "), radius " << fixed(lenses[k].radius, 1)
       << " px, zoom requested " << fixed(zoom_requested[k], 3)
       << ", measured on the geometric lens " << fixed(lenses[k].zoom, 3)
       << (methods.size() > 1
               ? "; every classic lens is matched to that zoom (same measure) and radius.\n"
               : "; the classic lenses are radial and do not apply to polygon and mask lenses, "
                 "whose regions below are taken in this disk.\n");
  }
  md << "\nShape distortion is s1/s2 - 1 of each triangle's source -> screen Jacobian (0 = shape "
        "kept), mean (weighted by source area) / max per region. Regions by source position: "
        "focus = within a r / zoom of the centre (what a flat-top lens of the same radius and "
        "zoom shows at full zoom on the inner fraction a of its disk), transition = the rest of "
        "the lens disk, "
        "context = outside. Zoom at centre = magnification_at the first lens's centre. Focus "
        "uniformity = max / min magnification over the focus triangles of a lens (the largest "
        "over the lenses). Occluded = source area not shown, percent of the image. — = no "
        "triangle in that region.\n\n";
  md << "| method | zoom at centre | focus uniformity | focus | transition | context | overall "
        "| occluded % | flipped |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Method& m : methods) {
    const RegionStatistics& r = m.regions;
    md << "| " << m.name << " | " << fixed(m.zoom_center, 3) << " | "
       << (r.focus_uniformity > 0 ? fixed(r.focus_uniformity, 3) : "—") << " | "
       << zone_cell(r.focus) << " | " << zone_cell(r.transition) << " | " << zone_cell(r.context)
       << " | " << zone_cell(r.overall) << " | " << fixed(r.occluded_percent, 2) << " | "
       << r.overall.flipped << " |\n";
  }
  md << "\nArea distortion, mean of max(a, 1/a) - 1 with a = s1 s2 the area scale (0 = area "
        "kept; the focus is magnified on purpose, so it is large there):\n\n";
  md << "| method | focus | transition | context |\n|---|---:|---:|---:|\n";
  for (const Method& m : methods) {
    md << "| " << m.name << " | " << area_cell(m.regions.focus) << " | "
       << area_cell(m.regions.transition) << " | " << area_cell(m.regions.context) << " |\n";
  }
  md << "\nPer lens, over the region given (focus_measure.h): zoom = mean magnification, "
        "uniformity = max / min, shape distortion mean / max, footprint = radius of the disk of "
        "the same area as the source disturbed by more than 5 %, moved = the largest displacement "
        "beyond the footprint (px):\n\n";
  md << "| method | lens | zoom | uniformity | shape | footprint | moved |\n"
        "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const Method& m : methods) {
    for (size_t k = 0; k < m.foci.size(); ++k) {
      const FocusMeasure& f = m.foci[k];
      md << "| " << m.name << " | " << k + 1 << " | " << fixed(f.zoom, 3) << " | "
         << fixed(f.uniformity, 3) << " | " << fixed(f.shape_mean, 3) << " / "
         << fixed(f.shape_max, 3) << " | " << fixed(f.footprint_radius, 0) << " | "
         << fixed(f.displacement_beyond_footprint, 1) << " |\n";
    }
  }
  md << "\nGeometric lens, the paper's Eq. 7 energy of its flattening (cot weights, measured from "
        "rigid): "
     << fixed(eq7_total, 1) << " px^2, " << fixed(eq7_total / image_area, 5)
     << " per source pixel.\n";
  return md.str();
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareArgs& a) {
  CLI::App* c = app.add_subcommand(
      "compare", "measure the geometric lens against the classic lenses at the same zoom");
  c->add_option("input", a.input, "input image (PNG or JPEG)")->required();
  c->add_option("-o,--output", a.output,
                "output folder (created if missing; its parent must exist)")
      ->required();
  cli::add_lens_options(*c, a.lens);
  c->add_option("--format", a.format, "image files: png or jpg")->capture_default_str();
  c->add_option("--jpeg-quality", a.jpeg_quality, "JPEG quality of --format jpg, in [1, 100]")
      ->capture_default_str();
  c->add_option("--tile", a.tile, "panel tile side in pixels, in [64, 1024]")
      ->capture_default_str();
  c->add_option("--baseline-mesh", a.baseline_mesh,
                "classic lens grid vertices along the long side, in [4, 1000]")
      ->capture_default_str();
  c->add_option("--heat-max", a.heat_max,
                "shape distortion drawn red (0: the largest over all methods)")
      ->capture_default_str();
  c->add_flag("--sweep", a.sweep,
              "one lens: its largest shape distortion against its footprint ratio (zoom + 1 to "
              "4 x zoom), the focus lens against every classic lens and the radial bound: "
              "sweep.json, sweep.md and a plot sweep.FORMAT");
  return c;
}

namespace {

// --sweep: the footprint sweep of one lens, written as JSON, Markdown and a plot.
int run_sweep(const CompareArgs& a, const fs::path& dir, const Image& source, const Lens& lens,
              const LensOptions& options, RunFiles& files) {
  const double z = lens.zoom;
  std::vector<double> ratios = {z + 1, 1.5 * z, 2 * z, 3 * z, 4 * z};
  std::sort(ratios.begin(), ratios.end());
  ratios.erase(std::unique(ratios.begin(), ratios.end()), ratios.end());
  const Sweep sweep =
      footprint_sweep(source.width, source.height, lens, options, ratios, a.baseline_mesh);
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream md;
  md << "# geolens compare --sweep: " << fs::path(a.input).filename().string() << "\n\n"
     << "Largest shape distortion s1/s2 - 1 of each method against the footprint ratio F (the "
        "focus lens's `--footprint`; every classic lens has radius F r and a flat top of the "
        "region's size), the focus uniformity (max / min magnification over the region) in "
        "brackets where it is above 1.01, and the radial bound 1 / (1 - ln zoom / ln F) - 1 at "
        "the zoom the focus lens reached.\n\n| F | zoom | bound |";
  std::vector<std::string> methods;
  for (const SweepPoint& p : sweep.points)
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end())
      methods.push_back(p.method);
  for (const std::string& m : methods) md << " " << m << " |";
  md << "\n|---:|---:|---:|";
  for (size_t m = 0; m < methods.size(); ++m) md << "---:|";
  md << "\n";
  for (size_t i = 0; i < sweep.ratios.size(); ++i) {
    const SweepPoint* geometric = nullptr;
    for (const SweepPoint& p : sweep.points)
      if (p.ratio == sweep.ratios[i] && p.method == "geometric") geometric = &p;
    md << "| " << fixed(sweep.ratios[i], 2) << " | " << fixed(geometric->zoom, 3) << " | "
       << fixed(sweep.bound[i], 3) << " |";
    for (const SweepPoint& p : sweep.points) {
      if (p.ratio != sweep.ratios[i]) continue;
      md << " " << fixed(p.shape_max, 3)
         << (p.uniformity > 1.01 ? " (" + fixed(p.uniformity, 2) + ")" : "") << " |";
      rows.push_back({{"method", p.method},
                      {"ratio", p.ratio},
                      {"zoom", p.zoom},
                      {"uniformity", p.uniformity},
                      {"shape_max", p.shape_max},
                      {"footprint_radius", p.footprint_radius},
                      {"bound", sweep.bound[i]}});
    }
    md << "\n";
  }
  save_image(files.staged((dir / ("sweep." + a.format)).string()), plot_sweep(sweep),
             a.jpeg_quality);
  write_file(files.staged((dir / "sweep.json").string()),
             nlohmann::json({{"points", rows}}).dump(2) + "\n");
  write_file(files.staged((dir / "sweep.md").string()), md.str());
  files.commit();
  return 0;
}

}  // namespace

int run_compare(const CompareArgs& a) {
  // Validate everything before any work.
  require(!a.output.empty(), "--output", "output folder must not be empty");
  fs::path dir = a.output;
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/" is the folder "out"
  require(a.format == "png" || a.format == "jpg", "--format",
          "expected png or jpg, got '" + a.format + "'");
  require(a.jpeg_quality >= 1 && a.jpeg_quality <= 100, "--jpeg-quality",
          "must be in [1, 100], got " + std::to_string(a.jpeg_quality));
  require(a.tile >= 64 && a.tile <= 1024, "--tile",
          "must be in [64, 1024], got " + std::to_string(a.tile));
  require_mesh_vertices(a.baseline_mesh, "--baseline-mesh");
  require(std::isfinite(a.heat_max) && a.heat_max >= 0, "--heat-max",
          "must be >= 0, got " + std::to_string(a.heat_max));
  RunFiles files;
  files.add_input("the input image", a.input);
  for (const LensSpecFile& f : cli::lens_files(a.lens))
    files.add_input("the --lens " + f.kind + " file", f.path);
  files.add_folder("--output", dir.string());
  files.check();  // the folder; its files once the lenses tell which
  auto output = [&](const std::string& name) {
    files.add_output("--output", (dir / name).string());
  };
  const LensOptions options = cli::parse_options(a.lens);
  const Image source = load_image(a.input);
  const std::vector<Lens> lenses = cli::parse_lenses(a.lens, source);
  if (a.sweep) {
    require(lenses.size() == 1, "--sweep", "sweeps one lens, got " + std::to_string(lenses.size()));
    for (const char* name : {"sweep.json", "sweep.md"}) output(name);
    output("sweep." + a.format);
    files.check();
    return run_sweep(a, dir, source, lenses.front(), options, files);
  }
  // The classic lenses are radial: they take part when every lens is a circle.
  const bool classic = std::all_of(lenses.begin(), lenses.end(), [](const Lens& lens) {
    return lens.region.kind() == RegionKind::kCircle;
  });
  for (size_t k = 0; k < lenses.size() && classic; ++k) {
    for (size_t j = 0; j < k; ++j) {
      require((lenses[k].region.peak() - lenses[j].region.peak()).norm() >=
                  classic_radius(lenses[k], options) + classic_radius(lenses[j], options),
              "--lens",
              "lenses " + std::to_string(j + 1) + " and " + std::to_string(k + 1) +
                  " overlap; compare needs disjoint circles");
    }
  }
  std::vector<std::string> names = {"geometric"};
  if (classic)
    for (ClassicLens kind : kClassicLenses) names.push_back(to_string(kind));
  for (const std::string& name : names) {
    output(name + "." + a.format);
    output(name + "_heatmap." + a.format);
  }
  output("panel." + a.format);
  for (const char* name : {"report.json", "report.md"}) output(name);
  files.check();

  // The geometric lens, then the classic lenses matched to its measured zoom.
  const GeometricLens geometric(source.width, source.height, options);
  const LensResult solved = geometric.solve(lenses);
  cli::warn_about_zooms(lenses, solved);
  std::vector<CircleLens> targets;
  std::vector<double> zoom_requested, measure_radius;
  for (size_t k = 0; k < lenses.size(); ++k) {
    targets.push_back(classic_target(lenses[k], options, std::max(1.0, solved.zoom_measured[k])));
    zoom_requested.push_back(lenses[k].zoom);
    // The radius GeometricLens measures its zoom over: a grid cell of the solved area, at least
    // 0.05 r (docs/design.md, "Zoom, not height").
    const double cell = solved.box.sizes().maxCoeff() / (options.mesh - 1);
    measure_radius.push_back(std::max(cell, 0.05 * lenses[k].region.size()));
  }
  std::vector<Method> methods;
  methods.push_back({"geometric", solved.warp, solved.zoom_measured[0], {}, {}, {}});
  for (ClassicLens kind : kClassicLenses) {
    if (!classic) break;
    MatchedClassicLens matched = match_classic_lens(kind, targets, measure_radius, source.width,
                                                    source.height, a.baseline_mesh);
    methods.push_back(
        {to_string(kind), std::move(matched.warp), matched.zoom_measured[0], {}, {}, {}});
  }
  double heat_max = a.heat_max;
  for (Method& m : methods) {
    m.measures = measure_triangles(m.warp);
    m.regions = measure_regions(m.warp, m.measures, targets, source.width, source.height);
    m.foci = measure_foci(m.warp, m.measures, lenses);
    if (a.heat_max == 0) heat_max = std::max(heat_max, m.regions.overall.conformal_max);
  }
  if (heat_max == 0) heat_max = 1;  // every method is the identity
  // Over the solved mesh (with --extent local, the patch; the warp adds an identity frame).
  const double eq7_total = eq7_energy(solved.lifted, solved.mesh.F, solved.flat).sum();

  nlohmann::json report = {{"methods", nlohmann::json::array()}};
  for (const Method& m : methods) {
    const RegionStatistics& r = m.regions;
    report["methods"].push_back(
        {{"name", m.name},
         {"zoom_center", m.zoom_center},
         {"focus_uniformity",
          r.focus_uniformity > 0 ? nlohmann::json(r.focus_uniformity) : nlohmann::json(nullptr)},
         {"distortion",
          {{"focus", zone_json(r.focus)},
           {"transition", zone_json(r.transition)},
           {"context", zone_json(r.context)},
           {"overall", zone_json(r.overall)}}},
         {"occluded_percent", r.occluded_percent},
         {"flipped", r.overall.flipped},
         {"lenses", foci_json(m.foci)}});
  }
  const std::string markdown = report_markdown(a, targets, zoom_requested, methods, eq7_total,
                                               double(source.width) * source.height);

  // Every output to a temporary file; all renamed into place once every one is written.
  const MipPyramid pyramid(source);
  RenderOptions render_options;
  render_options.width = source.width;
  render_options.height = source.height;
  for (const Method& m : methods) {
    const Image image = to_rgb(render(m.warp, pyramid, render_options));
    save_image(files.staged((dir / (m.name + "." + a.format)).string()), image, a.jpeg_quality);
    save_image(
        files.staged((dir / (m.name + "_heatmap." + a.format)).string()),
        with_legend(heatmap(m.warp, m.measures.conformal, m.measures.flipped, image, heat_max),
                    heat_max, m.name + ": shape distortion s1/s2 - 1"),
        a.jpeg_quality);
  }
  save_image(files.staged((dir / ("panel." + a.format)).string()),
             make_panel(source, pyramid, methods, targets, heat_max, a.tile), a.jpeg_quality);
  write_file(files.staged((dir / "report.json").string()), report.dump(2) + "\n");
  write_file(files.staged((dir / "report.md").string()), markdown);
  files.commit();
  return 0;
}

}  // namespace geolens
