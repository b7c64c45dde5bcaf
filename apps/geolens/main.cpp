// geolens: magnify regions of an image with the geometric focus+context lens.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "compare.h"
#include "geolens/core/errors.h"
#include "geolens/eval/run_stats.h"
#include "geolens/io/file_io.h"
#include "geolens/io/geojson.h"
#include "geolens/io/image.h"
#include "geolens/io/mesh_io.h"
#include "geolens/io/run_files.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "geolens/render/annotate.h"
#include "geolens/render/overlay.h"
#include "geolens/render/render.h"
#include "interrupt.h"
#include "lens_args.h"
#include "map.h"
#include "source_args.h"

using namespace geolens;

namespace {

struct MagnifyArgs {
  std::string input, output, stats, export_mesh, before_after, overlay;
  cli::SourceArgs source;
  cli::LensArgs lens;
};

// The run's inputs and outputs, each checked: an output naming an input, or written twice, is
// refused before any work (RunFiles::check).
void add_magnify_files(RunFiles& files, const MagnifyArgs& a) {
  require(is_writable_image_path(a.output), "--output",
          "'" + a.output + "' must end in .png, .jpg or .jpeg");
  if (!a.before_after.empty())
    require(is_writable_image_path(a.before_after), "--before-after",
            "'" + a.before_after + "' must end in .png, .jpg or .jpeg");
  cli::add_source_inputs(files, a.input, a.source);
  if (!a.overlay.empty()) files.add_input("the --overlay file", a.overlay);
  for (const LensSpecFile& f : cli::lens_files(a.lens))
    files.add_input("the --lens " + f.kind + " file", f.path);
  files.add_output("--output", a.output);
  if (!a.before_after.empty()) files.add_output("--before-after", a.before_after);
  if (!a.export_mesh.empty()) {
    files.add_output("--export-mesh", a.export_mesh + "_3d.obj");
    files.add_output("--export-mesh", a.export_mesh + "_flat.obj");
  }
  if (!a.stats.empty()) files.add_output("--stats", a.stats);
}

// The warnings of a warp's measured distortion: folded or collapsed triangles.
void warn_about_distortion(const DistortionSummary& distortion) {
  if (distortion.flipped > 0) {
    std::cerr << "geolens: warning: " << distortion.flipped
              << " triangles are flipped (folded); try --texture cotan, a lower zoom or a finer "
                 "--mesh\n";
  }
  if (distortion.degenerate()) {
    std::cerr << "geolens: warning: some triangles collapsed (conformal maximum "
              << distortion.conformal_max
              << "): the distortion figures are not meaningful; try --model focus, a lower zoom "
                 "or a finer --mesh\n";
  }
}

// The pictures and meshes of the run to temporary files, renamed into place by files.commit().
void stage_images(RunFiles& files, const MagnifyArgs& a, const Image& output, const Image& before,
                  const LensResult& result) {
  save_image(files.staged(a.output), output);
  if (!a.before_after.empty())
    save_image(files.staged(a.before_after), side_by_side(before, output));
  if (!a.export_mesh.empty()) {
    write_obj(files.staged(a.export_mesh + "_3d.obj"), result.lifted, result.mesh.F);
    write_obj(files.staged(a.export_mesh + "_flat.obj"), result.flat, result.mesh.F);
  }
}

// Milliseconds since the last call (or the construction).
class Lap {
 public:
  double operator()() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - mark_).count();
    mark_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point mark_ = std::chrono::steady_clock::now();
};

int run_magnify(const MagnifyArgs& a) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  // Validate everything before any work.
  RunFiles files;
  const cli::RemoveOnInterrupt interrupt(files);
  add_magnify_files(files, a);
  files.check();
  const LensOptions options = cli::parse_options(a.lens);
  // Each part of the run timed from the end of the one before (RunTimings, eval/run_stats.h).
  RunTimings timings;
  Lap lap;
  std::optional<VectorData> overlay =
      a.overlay.empty() ? std::nullopt
                        : std::optional(read_geojson(a.overlay, cli::max_points(a.source)));
  const SourceFile source = cli::open_input(a.input, a.source);
  // Over a vector map the overlay is in degrees, placed on its frame.
  if (overlay && source.map_frame)
    overlay = to_frame_pixels(*overlay, *source.map_frame, a.overlay);
  const int frame_width = source.frame_width, frame_height = source.frame_height;
  const std::vector<Lens> lenses = cli::parse_lenses(a.lens, frame_width, frame_height);
  cli::warn_about_unread_options(options, lenses);
  const auto [width, height] = cli::output_size(source, a.source);
  timings.load = lap();

  const GeometricLens lens(frame_width, frame_height, options);
  const LensResult result = lens.solve(lenses);
  lap();
  cli::warn_about_zooms(lenses, result);
  const DistortionSummary distortion = summarize(measure_triangles(result.warp));
  warn_about_distortion(distortion);
  timings.measure = lap();

  RenderOptions render_options;
  render_options.width = width;
  render_options.height = height;
  render_options.threads = options.flatten.threads;
  // A warp rendered with the source's own overlay (a vector map's labels), then the --overlay
  // features, mapped through the warp as rendered (grey made RGB).
  auto picture = [&](const WarpMesh& warp) {
    Image image = render(warp, source, render_options);
    if (overlay) {
      if (image.channels < 3) image = to_rgb(image);
      const MappedFeatures mapped = map_features(*overlay, framed_warp_map(warp, width, height));
      if (&warp == &result.warp)
        warn_about_losses(mapped.losses, "the overlay", "the source image");
      draw_overlay(image, mapped.data);
    }
    return image;
  };
  const Image output = picture(result.warp);
  // The source's counters for the output (the before picture reads and draws more).
  std::vector<std::pair<std::string, double>> counters;
  if (source.counters) counters = source.counters();
  Image before;
  if (!a.before_after.empty()) {
    before = picture(identity_warp(frame_width, frame_height));
    std::vector<Region> regions;
    for (const Lens& l : lenses) regions.push_back(l.region);
    outline_regions(before, regions, Eigen::Vector2d::Zero(), double(width) / frame_width,
                    double(height) / frame_height);
  }
  timings.render = lap();

  // Every output to a temporary file; all renamed into place once every one is written.
  stage_images(files, a, output, before, result);
  timings.save = lap();
  if (!a.stats.empty()) {
    timings.total = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const RunSource run_source{source.kind, frame_width, frame_height, source.scale, counters};
    write_file(files.staged(a.stats),
               run_stats_json(lenses, options, result, distortion, timings, run_source));
  }
  files.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"geolens: magnify regions of an image with a geometric focus+context lens"};
  app.set_version_flag("--version", std::string("geolens ") + GEOLENS_VERSION);
  app.require_subcommand(1);
  MagnifyArgs a;
  CLI::App* magnify = app.add_subcommand("magnify", "magnify lens regions of an image");
  magnify
      ->add_option("input", a.input,
                   "input: an image (PNG or JPEG) or a source file (a tile folder, .levels, "
                   ".svg, .geojson, .obj, .ply, .nii, .nii.gz, .nrrd)")
      ->required();
  magnify->add_option("-o,--output", a.output, "output image (.png, .jpg)")->required();
  cli::add_lens_options(*magnify, a.lens);
  cli::add_source_options(*magnify, a.source,
                          "output size WxH (default: the input's frame); frames an input without "
                          "pixels of its own (SVG, vector map, 3D)");
  magnify->add_option("--stats", a.stats, "write run statistics as JSON");
  magnify->add_option("--export-mesh", a.export_mesh,
                      "write PREFIX_3d.obj (lifted) and PREFIX_flat.obj (flattened)");
  magnify->add_option("--before-after", a.before_after,
                      "write the input (lenses outlined) and the output side by side");
  magnify->add_option("--overlay", a.overlay,
                      "draw the features of a GeoJSON file (source pixels) over the output, "
                      "mapped through the lens");
  CompareArgs compare_args;
  CLI::App* compare = add_compare_command(app, compare_args);
  MapArgs map_args;
  CLI::App* map = add_map_command(app, map_args);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A first word that is no command: named, rather than CLI11's "A subcommand is required".
    const std::string first = argc > 1 ? argv[1] : "";
    if (!first.empty() && first[0] != '-' && app.get_subcommands().empty())
      std::cerr << "geolens: error: unknown command '" << first
                << "' (expected magnify, compare or map; see geolens --help)\n";
    else
      std::cerr << "geolens: error: " << e.what() << " (see geolens --help)\n";
    return 2;
  }
  try {
    if (magnify->parsed()) return run_magnify(a);
    if (compare->parsed()) return run_compare(compare_args);
    if (map->parsed()) return run_map(map_args);
  } catch (const InvalidInput& e) {
    std::cerr << "geolens: error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "geolens: failed: " << e.what() << '\n';
    return 1;
  }
  return 2;
}
