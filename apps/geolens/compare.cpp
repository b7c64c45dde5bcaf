#include "compare.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/eval/comparison.h"
#include "geolens/geometry/grid.h"
#include "geolens/io/file_io.h"
#include "geolens/io/image.h"
#include "geolens/io/run_files.h"
#include "geolens/render/render.h"
#include "interrupt.h"

namespace geolens {

namespace fs = std::filesystem;

CLI::App* add_compare_command(CLI::App& app, CompareArgs& a) {
  CLI::App* c = app.add_subcommand(
      "compare", "measure the geometric lens against the classic lenses at the same zoom");
  c->add_option("input", a.input, "input: an image (PNG or JPEG) or a source file (see magnify)")
      ->required();
  cli::add_source_options(*c, a.source,
                          "the frame WxH of an input without pixels of its own (SVG, vector "
                          "map, 3D); outputs are the frame's size");
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

int run_compare(const CompareArgs& a) {
  // Validate everything before any work.
  require(!a.output.empty(), "--output", "output folder must not be empty");
  fs::path dir = a.output;
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/" is the folder "out"
  require(a.format == "png" || a.format == "jpg", "--format",
          "expected png or jpg, got '" + a.format + "'");
  require(a.jpeg_quality >= 1 && a.jpeg_quality <= 100, "--jpeg-quality",
          "must be in [1, 100], got " + std::to_string(a.jpeg_quality));
  require_panel_tile(a.tile, "--tile");
  require_mesh_vertices(a.baseline_mesh, "--baseline-mesh");
  require(std::isfinite(a.heat_max) && a.heat_max >= 0, "--heat-max",
          "must be >= 0, got " + number_text(a.heat_max));
  RunFiles files;
  const cli::RemoveOnInterrupt interrupt(files);
  cli::add_source_inputs(files, a.input, a.source);
  for (const LensSpecFile& f : cli::lens_files(a.lens))
    files.add_input("the --lens " + f.kind + " file", f.path);
  files.add_folder("--output", dir.string());
  files.check();  // the folder; its files once the lenses tell which
  auto output = [&](const std::string& name) {
    const std::string path = (dir / name).string();
    files.add_output("--output", path);
    return path;
  };
  const LensOptions options = cli::parse_options(a.lens);
  const SourceFile source = cli::open_input(a.input, a.source);
  const int width = source.frame_width, height = source.frame_height;
  const std::vector<Lens> lenses = cli::parse_lenses(a.lens, width, height);
  cli::warn_about_unread_options(options, lenses);
  const std::string title = fs::path(a.input).filename().string();

  if (a.sweep) {
    require(lenses.size() == 1, "--sweep", "sweeps one lens, got " + std::to_string(lenses.size()));
    const std::string json = output("sweep.json"), md = output("sweep.md"),
                      plot = output("sweep." + a.format);
    files.check();
    const Lens& lens = lenses.front();
    const Sweep sweep =
        footprint_sweep(width, height, lens, options, sweep_ratios(lens.zoom), a.baseline_mesh);
    // Every output to a temporary file; all renamed into place once every one is written.
    save_image(files.staged(plot), plot_sweep(sweep), a.jpeg_quality);
    write_file(files.staged(json), sweep_json(sweep));
    write_file(files.staged(md), sweep_markdown(sweep, title));
    files.commit();
    return 0;
  }

  const std::vector<std::string> names = comparison_methods(lenses, options, "--lens");
  for (const std::string& name : names) {
    output(name + "." + a.format);
    output(name + "_heatmap." + a.format);
  }
  const std::string panel = output("panel." + a.format), json = output("report.json"),
                    md = output("report.md");
  files.check();

  const Comparison comparison = compare_lenses(width, height, lenses, options, a.baseline_mesh);
  cli::warn_about_zooms(lenses, comparison.geometric);
  const double heat_max = a.heat_max > 0 ? a.heat_max : comparison_heat_max(comparison);

  // Every output to a temporary file; all renamed into place once every one is written.
  for (const ComparedMethod& m : comparison.methods) {
    const Image image = comparison_output(comparison, m, source);
    save_image(files.staged((dir / (m.name + "." + a.format)).string()), image, a.jpeg_quality);
    save_image(files.staged((dir / (m.name + "_heatmap." + a.format)).string()),
               comparison_heatmap(m, image, heat_max), a.jpeg_quality);
  }
  save_image(files.staged(panel), comparison_panel(comparison, source, heat_max, a.tile),
             a.jpeg_quality);
  write_file(files.staged(json), comparison_json(comparison));
  write_file(files.staged(md), comparison_markdown(comparison, title));
  files.commit();
  return 0;
}

}  // namespace geolens
