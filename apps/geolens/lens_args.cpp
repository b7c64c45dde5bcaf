#include "lens_args.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "geolens/core/errors.h"
#include "geolens/lens/lens_options.h"
#include "geolens/lens/lens_spec.h"

namespace geolens::cli {

void add_lens_options(CLI::App& c, LensArgs& a) {
  c.add_option("--lens", a.lenses,
               "circle:CX,CY,R[:ZOOM] (source pixels), polygon:FILE[:ZOOM] (one 'x y' per line) "
               "or mask:FILE[:ZOOM] (non-zero = inside, each blob a lens); repeatable")
      ->required();
  c.add_option("--zoom", a.zoom, "zoom of lenses that give none, in [1, 8]")->capture_default_str();
  c.add_option("--profile", a.profile, "bump profile: gaussian, sphere or mesa")
      ->capture_default_str();
  c.add_option("--model", a.model,
               "focus (the region magnified as a whole, the context giving way within the "
               "footprint), lift (the paper's: lifted triangles, harmonic texture), field (the "
               "lift as a zoom field: any shape reaches its zoom at its peak) or auto (lift for "
               "circles only, else field)")
      ->capture_default_str();
  c.add_option("--footprint", a.footprint,
               "focus model: how far the context gives way, as the ratio of the footprint's "
               "reach to the region's from its centre, above the zoom (0: 2 x zoom)")
      ->capture_default_str();
  c.add_option("--mesh", a.mesh, "grid vertices along the long side, in [4, 1000]")
      ->capture_default_str();
  c.add_option(
       "--mesh-tolerance", a.mesh_tolerance,
       "focus model: the grid is refined where the lens's start strays from linear over "
       "a triangle by more than this, output pixels, or 1/400 of the smallest lens's reach, "
       ">= 0 (0: not refined)")
      ->capture_default_str();
  c.add_option("--subdivide", a.subdivide,
               "bisection rounds refining triangles the lift stretches, in [0, 8] (0: none)")
      ->capture_default_str();
  c.add_option("--metric", a.metric, "paper (Eq. 6 alpha blend) or spectrum (ARAP..ASAP)")
      ->capture_default_str();
  c.add_option("--alpha", a.alpha, "metric blend: paper [0, 1), spectrum [0, 1]")
      ->capture_default_str();
  c.add_option("--weights", a.weights, "flattening weights of the lift model: paper or cotan")
      ->capture_default_str();
  c.add_option("--texture", a.texture, "texture map weights of the lift model: cotan or mvc")
      ->capture_default_str();
  c.add_option("--boundary", a.boundary, "image border: sliding, fixed or free")
      ->capture_default_str();
  c.add_option("--extent", a.extent,
               "global (the whole image gives way) or local (a patch around the lenses)")
      ->capture_default_str();
  c.add_option("--extent-factor", a.extent_factor,
               "local patch half-side over the lens radius, in (1, 100]")
      ->capture_default_str();
  c.add_option("--tolerance", a.tolerance, "relative energy change that stops iterating")
      ->capture_default_str();
  c.add_option("--max-iterations", a.max_iterations, "cap on flattening iterations")
      ->capture_default_str();
  c.add_option("--threads", a.threads,
               "threads of the lens solve (and of magnify's rendering), >= 0 (0: all cores); "
               "the results do not depend on it")
      ->capture_default_str();
}

std::string option_flag(const std::string& option) {
  std::string text = "--" + option;
  std::replace(text.begin(), text.end(), '_', '-');
  return text;
}

LensOptions parse_options(const LensArgs& a) {
  LensOptions options;
  options.mesh = a.mesh;
  options.mesh_tolerance = a.mesh_tolerance;
  options.subdivision.max_levels = a.subdivide;
  options.extent = parse_extent(a.extent);
  options.extent_factor = a.extent_factor;
  options.model = parse_lens_model(a.model);
  options.texture = parse_texture_weights(a.texture);
  options.flatten.weights = parse_flatten_weights(a.weights);
  options.flatten.metric = parse_metric(a.metric);
  options.flatten.alpha = a.alpha;
  options.flatten.boundary = parse_boundary(a.boundary);
  options.flatten.tolerance = a.tolerance;
  options.flatten.max_iterations = a.max_iterations;
  options.flatten.threads = a.threads;
  naming_options([&] { validate(options); });
  require_zoom(a.zoom, "--zoom");
  parse_profile(a.profile);
  return options;
}

std::vector<Lens> parse_lenses(const LensArgs& a, int width, int height) {
  const Profile profile = parse_profile(a.profile);
  std::vector<Lens> lenses;
  for (const std::string& spec : a.lenses) {
    std::vector<std::string> warnings;
    for (Lens& lens : naming_options([&] {
           return parse_lens_spec(spec, a.zoom, profile, a.footprint, width, height, &warnings);
         }))
      lenses.push_back(std::move(lens));
    for (const std::string& w : warnings) std::cerr << "geolens: warning: " << w << "\n";
  }
  return lenses;
}

std::vector<Lens> parse_lenses(const LensArgs& a, const Image& source) {
  return parse_lenses(a, source.width, source.height);
}

std::vector<LensSpecFile> lens_files(const LensArgs& a) {
  std::vector<LensSpecFile> files;
  for (const std::string& spec : a.lenses)
    if (const std::optional<LensSpecFile> file = lens_spec_file(spec)) files.push_back(*file);
  return files;
}

// "WxH", each side in [1, 16384].
std::pair<int, int> parse_size(const std::string& text) {
  auto side = [&](const std::string& s) {
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    require(!s.empty() && end == s.c_str() + s.size() && v >= 1 && v <= 16384, "--size",
            "expected WxH with sides in [1, 16384], got '" + text + "'");
    return int(v);
  };
  const size_t x = text.find('x');
  require(x != std::string::npos, "--size", "expected WxH, got '" + text + "'");
  return {side(text.substr(0, x)), side(text.substr(x + 1))};
}

void warn_about_unread_options(const LensOptions& options, const std::vector<Lens>& lenses) {
  for (const UnreadOption& o : unread_options(options, lenses))
    std::cerr << "geolens: warning: " << option_flag(o.name) << " is ignored: " << o.reason
              << "; it is left out of the stats\n";
}

void warn_about_zooms(const std::vector<Lens>& lenses, const LensResult& result) {
  for (const std::string& line : zoom_warnings(lenses, result))
    std::cerr << "geolens: warning: " << line << "\n";
}

}  // namespace geolens::cli
