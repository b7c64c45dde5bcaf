#include "map.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <variant>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "geolens/io/geojson.h"
#include "geolens/io/image.h"
#include "geolens/io/point_csv.h"
#include "geolens/io/run_files.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/measure/distortion.h"
#include "interrupt.h"
#include "source_args.h"

namespace geolens {

namespace {

enum class Format { kCsv, kGeoJson };

std::optional<Format> format_of(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension == ".csv") return Format::kCsv;
  if (extension == ".geojson" || extension == ".json") return Format::kGeoJson;
  return std::nullopt;
}

const char* name_of(Format f) { return f == Format::kCsv ? "CSV" : "GeoJSON"; }

bool to_stdout(const MapArgs& a) { return a.output.empty() || a.output == "-"; }

// --format, else the input's extension, else the output's; the output's extension, if it names
// a format, must agree.
Format pick_format(const MapArgs& a) {
  std::optional<Format> f;
  if (!a.format.empty()) {
    require(a.format == "csv" || a.format == "geojson", "--format",
            "expected csv or geojson, got '" + a.format + "'");
    f = a.format == "csv" ? Format::kCsv : Format::kGeoJson;
  } else if (a.input != "-") {
    f = format_of(a.input);
    require(f.has_value(), "--format",
            "cannot tell the format of '" + a.input +
                "' from its extension (.csv, .geojson, .json): give --format csv or geojson");
  } else {
    if (!to_stdout(a)) f = format_of(a.output);
    require(f.has_value(), "--format",
            "reading standard input needs --format csv or geojson (or an --output with that "
            "extension)");
  }
  if (!to_stdout(a)) {
    const std::optional<Format> out = format_of(a.output);
    require(!out || *out == *f, "--output",
            "'" + a.output + "' is " + name_of(*out) + " but the data is " + name_of(*f) +
                " (the output has the input's format)");
  }
  return *f;
}

std::string standard_input() {
  std::stringstream text;
  text << std::cin.rdbuf();
  return text.str();
}

}  // namespace

CLI::App* add_map_command(CLI::App& app, MapArgs& a) {
  CLI::App* c = app.add_subcommand(
      "map", "map points (CSV) or features (GeoJSON) through the lens: source -> screen pixels");
  c->add_option("input", a.input,
                "CSV ('x,y' per line, optional header, further columns kept) or GeoJSON file; "
                "'-' reads standard input")
      ->required();
  c->add_option("-o,--output", a.output, "output file (default: standard output), never the input");
  cli::add_lens_options(*c, a.lens);
  c->add_option("--image", a.image,
                "the source image (or source file) the lenses are placed on (its size); a vector "
                "map (.geojson) places the input in longitude and latitude on its frame (and "
                "--inverse writes them)");
  c->add_option("--style", a.style, "style file (JSON) of an --image vector map (its frame)");
  c->add_option("--size", a.size,
                "output size WxH, as magnify's (default: the source's); without --image also "
                "the source's size");
  c->add_flag("--inverse", a.inverse, "map screen -> source pixels instead");
  c->add_option("--max-segment", a.max_segment,
                "longest segment of a line or ring before it is mapped, pixels of the input "
                "side, > 0")
      ->capture_default_str();
  c->add_option("--format", a.format, "csv or geojson (default: from the file extension)");
  c->add_option("--max-points", a.max_points,
                "the most points a CSV input, or positions a GeoJSON input or --image vector map, "
                "may hold, in [1, 2^30]; default " +
                    std::to_string(kMaxCsvPoints) + " (2^22; 2^22 took 0.8 GB)");
  return c;
}

void warn_about_losses(const MapLosses& losses, const std::string& what, const std::string& area) {
  if (!losses.any()) return;
  std::cerr << "geolens: warning: " << what << " is partly outside " << area << ": "
            << losses.points << " points dropped, " << losses.lines << " lines cut, "
            << losses.polygons << " polygons dropped\n";
}

// The run's inputs and output, each checked: an output naming an input is refused before any
// work (RunFiles::check).
void add_map_files(RunFiles& files, const MapArgs& a) {
  if (a.input != "-") files.add_input("the input", a.input);
  require(a.style.empty() || !a.image.empty(), "--style",
          "is the style of an --image vector map: give --image");
  if (!a.image.empty()) files.add_input("the --image", a.image);
  if (!a.style.empty()) files.add_input("the --style file", a.style);
  for (const LensSpecFile& f : cli::lens_files(a.lens))
    files.add_input("the --lens " + f.kind + " file", f.path);
  if (!to_stdout(a)) files.add_output("--output", a.output);
}

// `data` (named `name`) mapped through `map` as `a` asks, as CSV or GeoJSON text; on a vector
// map (`degrees`) the source side in degrees. What did not map goes to `losses`.
std::string mapped_text(const std::variant<PointTable, VectorData>& data, const WarpMap& map,
                        const MapArgs& a, const std::optional<MapFrame>& degrees,
                        const std::string& name, MapLosses& losses) {
  const MapDirection direction = a.inverse ? MapDirection::kInverse : MapDirection::kForward;
  // On a vector map the source side is in degrees: the input placed on its frame (forward), or
  // the output told in degrees (inverse).
  const bool from_degrees = degrees && !a.inverse, to_degrees_out = degrees && a.inverse;
  if (const PointTable* table = std::get_if<PointTable>(&data)) {
    MappedPoints mapped =
        map_points(from_degrees ? to_frame_pixels(*table, *degrees, name) : *table, map, direction);
    losses = mapped.losses;
    return point_csv_text(to_degrees_out ? to_degrees(mapped.table, *degrees) : mapped.table);
  }
  const VectorData& features = std::get<VectorData>(data);
  MappedFeatures mapped = cli::naming_options(
      [&] {
        return map_features(from_degrees ? to_frame_pixels(features, *degrees, name) : features,
                            map, MapOptions{direction, a.max_segment});
      },
      " (mapping '" + a.input + "')");
  losses = mapped.losses;
  return geojson_text(to_degrees_out ? to_degrees(mapped.data, *degrees) : mapped.data);
}

int run_map(const MapArgs& a) {
  // Everything checked and the input read before the lenses are solved.
  const Format format = pick_format(a);
  require(!a.image.empty() || !a.size.empty(), "map",
          "the lenses need the source's size: give --image FILE or --size WxH");
  // A hundredth of a pixel is finer than any output shows; 5e-5 made 8.4 GB of a 4.6 KB file.
  require(a.max_segment >= 0.01, "--max-segment",
          "must be at least 0.01 pixels, got " + number_text(a.max_segment));
  cli::SourceArgs source_args;  // of --image
  source_args.size = a.size;
  source_args.style = a.style;
  source_args.max_points = a.max_points;
  static_assert(kMaxCsvPoints == kMaxGeoJsonPoints, "one default for --max-points");
  const size_t max_points = cli::max_points(source_args);
  RunFiles files;
  const cli::RemoveOnInterrupt interrupt(files);
  add_map_files(files, a);
  files.check();
  const std::string name = a.input == "-" ? "standard input" : a.input;
  std::variant<PointTable, VectorData> data;
  if (format == Format::kCsv)
    data = a.input == "-" ? parse_point_csv(standard_input(), name, max_points)
                          : read_point_csv(a.input, max_points);
  else
    data = a.input == "-" ? parse_geojson(standard_input(), name, max_points)
                          : read_geojson(a.input, max_points);
  const LensOptions options = cli::parse_options(a.lens);
  std::pair<int, int> source_size, output_size;
  std::optional<MapFrame> degrees;  // a vector map's frame: the source side is in degrees
  if (!a.size.empty()) output_size = parse_size(a.size, "--size", 1, cli::kMaxSide);
  if (!a.image.empty()) {
    // Any source file: its frame is what the lenses are placed on (--size frames one without
    // pixels of its own).
    const SourceFile image = cli::open_input(a.image, source_args);
    source_size = {image.frame_width, image.frame_height};
    if (a.size.empty()) output_size = source_size;
    degrees = image.map_frame;
  } else {
    source_size = output_size;
  }
  const std::vector<Lens> lenses = cli::parse_lenses(a.lens, source_size.first, source_size.second);
  cli::warn_about_unread_options(options, lenses);

  const LensResult result =
      GeometricLens(source_size.first, source_size.second, options).solve(lenses);
  cli::warn_about_zooms(lenses, result);
  if (const int flipped = summarize(measure_triangles(result.warp)).flipped; flipped > 0)
    std::cerr << "geolens: warning: " << flipped
              << " triangles are flipped (folded): where they fold, a screen point shows several "
                 "source points and --inverse gives one of them\n";
  const WarpMap map = framed_warp_map(result.warp, output_size.first, output_size.second);
  MapLosses losses;
  const std::string text = mapped_text(data, map, a, degrees, name, losses);
  warn_about_losses(losses, "the input", a.inverse ? "the output frame" : "the source image");
  if (to_stdout(a)) {
    std::cout << text << std::flush;
    if (!std::cout) throw IoError("map: cannot write to standard output");
    return 0;
  }
  write_file(files.staged(a.output), text);
  files.commit();
  return 0;
}

}  // namespace geolens
