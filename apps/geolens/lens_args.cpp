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
  c.add_option("--footprint", a.footprint,
               "focus model: how far the context gives way, as the ratio of the footprint's "
               "reach to the region's from its centre, above the zoom (0: 2 x zoom)")
      ->capture_default_str();
  const LensOptions defaults;
  for (const LensOptionField& field : lens_option_fields()) {
    if (field.name == "draft_mesh") continue;
    std::string& value = a.options[field.name] = field.get(defaults);
    c.add_option(option_flag(field.name), value, field.help)
        ->type_name(field.type == LensOptionField::Type::kInteger  ? "INT"
                    : field.type == LensOptionField::Type::kNumber ? "FLOAT"
                                                                   : "TEXT")
        ->capture_default_str();
  }
}

LensOptions parse_options(const LensArgs& a) {
  LensOptions options;
  naming_options([&] {
    for (const auto& [name, text] : a.options) lens_option_field(name).set(options, text);
    validate(options);
  });
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
