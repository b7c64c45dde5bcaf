#include "geolens/lens/lens_spec.h"

#include <cmath>
#include <cstdlib>
#include <optional>

#include "geolens/core/errors.h"
#include "geolens/core/parse.h"
#include "geolens/io/image.h"
#include "geometry/polygon.h"

namespace geolens {

const char* const kLensSpecSyntax =
    "circle:CX,CY,R[:ZOOM], polygon:FILE[:ZOOM] or mask:FILE[:ZOOM]";

namespace {

constexpr const char* kFunction = "parse_lens_spec";

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1)
    parts.push_back(text.substr(start, at - start));
  parts.push_back(text.substr(start));
  return parts;
}

double number(const std::string& text, const std::string& what, const std::string& spec) {
  const std::optional<double> value = read_number(text);
  require(value.has_value(), kFunction, what + " '" + text + "' in '" + spec + "' is not a number");
  return *value;
}

std::vector<Region> parse_regions(const std::vector<std::string>& parts, const std::string& spec,
                                  int width, int height, std::vector<std::string>* warnings) {
  if (parts[0] == "circle") {
    const std::vector<std::string> numbers = split(parts[1], ',');
    require(numbers.size() == 3, kFunction,
            std::string("expected ") + kLensSpecSyntax + ", got '" + spec + "'");
    const double radius = number(numbers[2], "radius", spec);
    require(std::isfinite(radius) && radius > 0, kFunction,
            "radius must be a positive number, got '" + numbers[2] + "' in '" + spec + "'");
    const Eigen::Vector2d centre(number(numbers[0], "centre x", spec),
                                 number(numbers[1], "centre y", spec));
    require(centre.allFinite(), kFunction,
            "the centre must be finite numbers, got '" + numbers[0] + "," + numbers[1] + "' in '" +
                spec + "'");
    return {Region::circle(centre, radius)};
  }
  if (parts[0] == "polygon") {
    // Vertices within a tenth of a pixel of the outline without them add nothing a picture
    // shows, and cost: a circle written as 10 000 vertices took 63 s and failed with degenerate
    // triangles between vertices 0.09 px apart; simplified, it has 96 and solves as a circle.
    const std::vector<Eigen::Vector2d> read = read_polygon_file(parts[1]);
    // Named by its file from here on: "polygon 'p.txt': edge 0 ... and edge 2 ... intersect".
    const std::string polygon = "polygon '" + parts[1] + "'";
    for (size_t i = 0; i < read.size(); ++i)
      require(read[i].x() >= 0 && read[i].x() <= width && read[i].y() >= 0 && read[i].y() <= height,
              polygon.c_str(),
              "vertex " + std::to_string(i + 1) + " (" + number_text(read[i].x()) + ", " +
                  number_text(read[i].y()) + ") is outside the " + std::to_string(width) + "x" +
                  std::to_string(height) + " image");
    // Checked as read (repeated vertices aside) before it is simplified, whose splits are
    // quadratic on a self-intersecting zigzag of 100 000 vertices (45 s), then as simplified.
    std::vector<Eigen::Vector2d> distinct;
    for (const Eigen::Vector2d& v : read)
      if (distinct.empty() || v != distinct.back()) distinct.push_back(v);
    if (distinct.size() > 1 && distinct.front() == distinct.back()) distinct.pop_back();
    validate_polygon(distinct, polygon.c_str());
    const std::vector<Eigen::Vector2d> vertices = simplify_loop(distinct, kPolygonTolerance);
    // A polygon simplified to a segment was one (of zero area): named so, as read.
    validate_polygon(vertices.size() < 3 ? distinct : vertices, polygon.c_str());
    return {Region::polygon(vertices)};
  }
  if (parts[0] == "mask") {
    const Image mask = load_mask(parts[1]);
    require(mask.width == width && mask.height == height, kFunction,
            "mask '" + parts[1] + "' is " + std::to_string(mask.width) + "x" +
                std::to_string(mask.height) + " but the image is " + std::to_string(width) + "x" +
                std::to_string(height));
    size_t dropped = 0;
    std::vector<Region> blobs;
    try {
      blobs = Region::from_mask(mask, &dropped);
    } catch (const InvalidInput& e) {  // "Region::from_mask: what" said of the file
      const std::string what = e.what();
      throw InvalidInput("mask '" + parts[1] + "': " + what.substr(what.find(": ") + 2));
    }
    if (dropped > 0 && warnings)
      warnings->push_back("mask '" + parts[1] + "': " + std::to_string(dropped) + " blob" +
                          (dropped == 1 ? "" : "s") + " of fewer than " +
                          std::to_string(Region::kMinMaskBlobPixels) +
                          " pixels left out (speckle); " + std::to_string(blobs.size()) + " lens" +
                          (blobs.size() == 1 ? "" : "es") + " kept");
    return blobs;
  }
  throw InvalidInput(std::string(kFunction) + ": expected " + kLensSpecSyntax + ", got '" + spec +
                     "'");
}

}  // namespace

std::vector<Lens> parse_lens_spec(const std::string& spec, double default_zoom, Profile profile,
                                  double footprint, int width, int height,
                                  std::vector<std::string>* warnings) {
  const std::vector<std::string> parts = split(spec, ':');
  require(parts.size() >= 2 && parts.size() <= 3, kFunction,
          std::string("expected ") + kLensSpecSyntax + ", got '" + spec + "'");
  const double zoom = parts.size() == 3 ? number(parts[2], "zoom", spec) : default_zoom;
  std::vector<Lens> lenses;
  for (Region& region : parse_regions(parts, spec, width, height, warnings)) {
    lenses.push_back(Lens{std::move(region), zoom, profile, footprint});
    validate_lens(lenses.back(), width, height);
  }
  return lenses;
}

std::optional<LensSpecFile> lens_spec_file(const std::string& spec) {
  const std::vector<std::string> parts = split(spec, ':');
  if (parts.size() >= 2 && parts.size() <= 3 && (parts[0] == "polygon" || parts[0] == "mask"))
    return LensSpecFile{parts[0], parts[1]};
  return std::nullopt;
}

}  // namespace geolens
