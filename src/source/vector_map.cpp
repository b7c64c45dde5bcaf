#include "source/vector_map.h"

#include <cairo.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/geojson.h"
#include "geolens/source/map_style.h"
#include "geolens/source/source.h"
#include "source/cairo_tile.h"
#include "source/map_labels.h"

namespace geolens {

namespace {

using Json = nlohmann::json;

constexpr int kMaxFrame = 16384;
constexpr double kPi = 3.14159265358979323846;

struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
  void add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool meets(const Box& b) const { return x0 <= b.x1 && b.x0 <= x1 && y0 <= b.y1 && b.y0 <= y1; }
  bool empty() const { return !(x0 <= x1 && y0 <= y1); }
};

/// A path of frame pixels and its bounding box.
struct Path {
  Eigen::MatrixX2d points;
  Box box;
};

/// What a geometry draws as: dots, strokes, or a filled area of rings (even-odd).
enum class Kind { kPoints, kLines, kArea };

struct Part {
  Kind kind;
  std::vector<Path> paths;
};

struct Layer {
  MapLayerStyle style;
  std::vector<size_t> features;  ///< the features it selects, indices
};

/// Everything a tile is drawn from; read-only once built.
struct MapData {
  std::vector<std::vector<Part>> features;  ///< the parts of each feature, frame pixels
  std::vector<Box> feature_boxes;
  std::vector<Layer> layers;
  std::array<uint8_t, 3> background;
  double scale;
  double max_reach;  ///< texels a stroke or dot reaches beyond its path: culling margin
};

void add_parts(const Geometry& g, std::vector<Part>& parts) {
  switch (g.type) {
    case GeometryType::kPoint:
    case GeometryType::kMultiPoint:
      parts.push_back({Kind::kPoints, {}});
      break;
    case GeometryType::kLineString:
    case GeometryType::kMultiLineString:
      parts.push_back({Kind::kLines, {}});
      break;
    case GeometryType::kPolygon:
    case GeometryType::kMultiPolygon:
      parts.push_back({Kind::kArea, {}});
      break;
    case GeometryType::kGeometryCollection:
      for (const Geometry& m : g.members) add_parts(m, parts);
      return;
  }
  for (const Eigen::MatrixX2d& p : g.paths) parts.back().paths.push_back({p, {}});
}

bool selects(const MapLayerStyle& layer, const std::vector<std::vector<Json>>& wanted,
             const Json& properties) {
  for (size_t c = 0; c < layer.where.size(); ++c) {
    if (!properties.is_object()) return false;
    const auto value = properties.find(layer.where[c].key);
    if (value == properties.end()) return false;
    if (std::none_of(wanted[c].begin(), wanted[c].end(),
                     [&](const Json& w) { return w == *value; }))
      return false;
  }
  return true;
}

void set_color(cairo_t* cr, const MapColor& c) { cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a); }

/// Strokes the current path `width` device pixels wide, whatever the user transform.
void stroke_device(cairo_t* cr, const MapColor& color, double width) {
  cairo_save(cr);
  cairo_identity_matrix(cr);
  set_color(cr, color);
  cairo_set_line_width(cr, width);
  cairo_stroke(cr);
  cairo_restore(cr);
}

void add_path(cairo_t* cr, const Eigen::MatrixX2d& p, bool close) {
  cairo_move_to(cr, p(0, 0), p(0, 1));
  for (Eigen::Index i = 1; i < p.rows(); ++i) cairo_line_to(cr, p(i, 0), p(i, 1));
  if (close) cairo_close_path(cr);
}

/// Whether a layer of `style` draws parts of `kind`.
bool draws(const MapLayerStyle& style, Kind kind) {
  using G = MapLayerStyle::Geometry;
  switch (style.geometry) {
    case G::kAny:
      return true;
    case G::kPoint:
      return kind == Kind::kPoints;
    case G::kLine:
      return kind == Kind::kLines;
    case G::kPolygon:
      return kind == Kind::kArea;
  }
  return false;
}

/// Draws the parts of one feature that meet `view` (frame pixels) in `style`.
void draw_feature(cairo_t* cr, const std::vector<Part>& parts, const MapLayerStyle& style,
                  const Box& view) {
  const bool stroke = style.stroke && style.width > 0;
  for (const Part& part : parts) {
    if (!draws(style, part.kind)) continue;
    cairo_new_path(cr);
    if (part.kind == Kind::kArea) {
      if (!style.fill && !stroke) continue;
      for (const Path& ring : part.paths)
        if (ring.box.meets(view)) add_path(cr, ring.points, true);
      if (style.fill) {
        set_color(cr, *style.fill);
        cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
        stroke ? cairo_fill_preserve(cr) : cairo_fill(cr);
      }
      if (stroke) stroke_device(cr, *style.stroke, style.width);
    } else if (part.kind == Kind::kLines) {
      if (!stroke) continue;
      for (const Path& line : part.paths)
        if (line.box.meets(view)) add_path(cr, line.points, false);
      stroke_device(cr, *style.stroke, style.width);
    } else {
      // A labelled layer's points are drawn with their labels, upright (MapDot).
      if (style.label || style.radius <= 0 || (!style.fill && !stroke)) continue;
      for (const Path& points : part.paths) {
        if (!points.box.meets(view)) continue;
        for (Eigen::Index i = 0; i < points.points.rows(); ++i) {
          double x = points.points(i, 0), y = points.points(i, 1);
          cairo_user_to_device(cr, &x, &y);
          cairo_save(cr);
          cairo_identity_matrix(cr);
          cairo_new_path(cr);
          cairo_arc(cr, x, y, style.radius, 0, 2 * kPi);
          if (style.fill) {
            set_color(cr, *style.fill);
            stroke ? cairo_fill_preserve(cr) : cairo_fill(cr);
          }
          if (stroke) stroke_device(cr, *style.stroke, style.width);
          cairo_restore(cr);
        }
      }
    }
  }
  cairo_new_path(cr);
}

Image draw_tile(const MapData& map, const TileRequest& request) {
  const double texels_per_frame = map.scale / double(int64_t(1) << request.level);
  const double zoom = texels_per_frame;  // the level is shown 1:1 at this magnification
  const double margin = (map.max_reach + 1) / texels_per_frame;
  Box view;
  view.add(request.x / texels_per_frame - margin, request.y / texels_per_frame - margin);
  view.add((request.x + request.width) / texels_per_frame + margin,
           (request.y + request.height) / texels_per_frame + margin);
  return cairo_tile(
      request, map.scale, map.background,
      [&](cairo_t* cr) {
        cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
        for (const Layer& layer : map.layers) {
          if (zoom < layer.style.min_zoom || zoom >= layer.style.max_zoom) continue;
          for (size_t f : layer.features)
            if (map.feature_boxes[f].meets(view))
              draw_feature(cr, map.features[f], layer.style, view);
        }
      },
      "vector_map_source");
}

/// The map's tiles' data, its labels and its frame.
struct BuiltMap {
  std::shared_ptr<MapData> map;
  std::shared_ptr<std::vector<MapLabel>> labels;
  std::shared_ptr<std::vector<MapDot>> dots;
  int width, height;
  MapFrame frame;
};

/// Projects every feature's parts into map.features (still y north), each point checked to be
/// degrees; returns their extent, left empty when the style gives the extent.
Box project_features(const VectorData& data, const MapStyle& style, const char* function,
                     MapData& map) {
  Box extent;
  map.features.resize(data.features.size());
  for (size_t f = 0; f < data.features.size(); ++f) {
    if (!data.features[f].geometry) continue;
    add_parts(*data.features[f].geometry, map.features[f]);
    for (Part& part : map.features[f])
      for (Path& path : part.paths)
        for (Eigen::Index i = 0; i < path.points.rows(); ++i) {
          const Eigen::Vector2d d = checked_degrees(path.points(i, 0), path.points(i, 1), function,
                                                    "feature " + std::to_string(f));
          const Eigen::Vector2d p = project(style.projection, d.x(), d.y());
          path.points.row(i) = p.transpose();
          if (!style.extent) extent.add(p.x(), p.y());
        }
  }
  return extent;
}

/// The extent to frame: the points' `extent`, or the style's projected, refused if empty, and
/// padded where flat so that a single point or a straight line still gets an area around it.
Box framed_extent(Box extent, const MapStyle& style, const char* function) {
  if (style.extent) {
    const auto& e = *style.extent;
    const Eigen::Vector2d a = project(style.projection, e[0], e[1]);
    const Eigen::Vector2d b = project(style.projection, e[2], e[3]);
    extent.add(a.x(), a.y());
    extent.add(b.x(), b.y());
  }
  require(!extent.empty(), function, "nothing to frame: the data has no coordinates");
  const double pad = style.projection == MapProjection::kPlateCarree ? 0.01 : 0.01 * kPi / 180;
  if (extent.x1 - extent.x0 <= 0) extent.x0 -= pad, extent.x1 += pad;
  if (extent.y1 - extent.y0 <= 0) extent.y0 -= pad, extent.y1 += pad;
  return extent;
}

/// The frame of width x height pixels that shows `extent` centred, never stretched; a side given
/// as 0 is set from the extent's aspect (both: kVectorMapDefaultWidth wide), refused outside
/// [1, 16384].
MapFrame fit_frame(const Box& extent, MapProjection projection, int& width, int& height,
                   const char* function) {
  const double dx = extent.x1 - extent.x0, dy = extent.y1 - extent.y0;
  if (width == 0 && height == 0) width = kVectorMapDefaultWidth;
  // The side set from the aspect is checked as a double: a huge one would wrap in an int.
  const double w = width != 0 ? width : std::round(height * dx / dy);
  const double h = height != 0 ? height : std::round(width * dy / dx);
  require(w >= 1 && h >= 1 && w <= kMaxFrame && h <= kMaxFrame, function,
          "the extent's aspect gives a frame of " + number_text(w) + " x " + number_text(h) +
              " pixels, outside [1, 16384]: give both sides of the size");
  width = int(w);
  height = int(h);
  MapFrame frame;
  frame.projection = projection;
  frame.left = extent.x0;
  frame.top = extent.y1;
  frame.scale = std::min(width / dx, height / dy);  // the extent centred, never stretched
  frame.offset = {(width - frame.scale * dx) / 2, (height - frame.scale * dy) / 2};
  return frame;
}

/// Moves every point of map.features from projected coordinates to the frame's pixels, and
/// sets the paths' and the features' boxes.
void move_to_frame_pixels(const MapFrame& frame, MapData& map) {
  map.feature_boxes.resize(map.features.size());
  for (size_t f = 0; f < map.features.size(); ++f)
    for (Part& part : map.features[f])
      for (Path& path : part.paths) {
        for (Eigen::Index i = 0; i < path.points.rows(); ++i) {
          path.points.row(i) = frame.from_projected(path.points.row(i).transpose()).transpose();
          path.box.add(path.points(i, 0), path.points(i, 1));
        }
        map.feature_boxes[f].add(path.box.x0, path.box.y0);
        map.feature_boxes[f].add(path.box.x1, path.box.y1);
      }
}

/// The label's text for a feature's `properties`: the first of its text properties that is a
/// non-empty string, or empty.
std::string label_text(const MapLabelStyle& label, const Json& properties) {
  for (const std::string& key : label.text) {
    const auto t = properties.find(key);
    if (t != properties.end() && t->is_string() && !t->get<std::string>().empty())
      return t->get<std::string>();
  }
  return std::string();
}

/// Adds the dots and labels of a feature (`parts`, `properties`) that labelled layer `s` selects:
/// a dot at each point it draws if it has a radius, a label there if the feature has its text.
void add_labels(const MapLayerStyle& s, const std::vector<Part>& parts, const Json& properties,
                std::vector<MapLabel>& labels, std::vector<MapDot>& dots) {
  if (s.radius > 0)
    for (const Part& part : parts)
      if (part.kind == Kind::kPoints && draws(s, part.kind))
        for (const Path& path : part.paths)
          for (Eigen::Index i = 0; i < path.points.rows(); ++i)
            dots.push_back({path.points.row(i).transpose(), s.radius, s.fill, s.stroke, s.width,
                            s.min_zoom, s.max_zoom});
  if (!properties.is_object()) return;
  const std::string text = label_text(*s.label, properties);
  if (text.empty()) return;
  const auto r = properties.find(s.label->rank);
  const double rank = r != properties.end() && r->is_number() ? r->get<double>() : 0;
  for (const Part& part : parts) {
    if (part.kind != Kind::kPoints || !draws(s, part.kind)) continue;
    for (const Path& path : part.paths)
      for (Eigen::Index i = 0; i < path.points.rows(); ++i)
        labels.push_back({path.points.row(i).transpose(), text, rank, s.radius + 2, *s.label,
                          s.min_zoom, s.max_zoom});
  }
}

/// Sets map.layers, each style layer's selection of the features by their properties, and
/// map.max_reach; adds the labelled layers' dots and labels.
void select_layers(const VectorData& data, const MapStyle& style, MapData& map,
                   std::vector<MapLabel>& labels, std::vector<MapDot>& dots) {
  std::vector<Json> properties(data.features.size());
  for (size_t f = 0; f < data.features.size(); ++f)
    properties[f] = Json::parse(data.features[f].properties, nullptr, false);
  map.max_reach = 0;
  for (const MapLayerStyle& s : style.layers) {
    Layer layer{s, {}};
    std::vector<std::vector<Json>> wanted;
    for (const auto& c : s.where) {
      wanted.emplace_back();
      for (const std::string& v : c.values) wanted.back().push_back(Json::parse(v));
    }
    for (size_t f = 0; f < data.features.size(); ++f)
      if (selects(s, wanted, properties[f])) layer.features.push_back(f);
    map.max_reach = std::max(map.max_reach, s.radius + s.width / 2);
    if (s.label)
      for (size_t f : layer.features) add_labels(s, map.features[f], properties[f], labels, dots);
    map.layers.push_back(std::move(layer));
  }
}

BuiltMap build_map(const VectorData& data, const MapStyle& style, int width, int height,
                   const char* function) {
  require(width >= 0 && height >= 0 && width <= kMaxFrame && height <= kMaxFrame, function,
          "the size " + std::to_string(width) + " x " + std::to_string(height) +
              " is not in [0, 16384]");
  const std::string problem = vector_data_problem(data);
  require(problem.empty(), function, problem);

  auto map = std::make_shared<MapData>();
  const Box extent = framed_extent(project_features(data, style, function, *map), style, function);
  const MapFrame frame = fit_frame(extent, style.projection, width, height, function);
  move_to_frame_pixels(frame, *map);
  auto labels = std::make_shared<std::vector<MapLabel>>();
  auto dots = std::make_shared<std::vector<MapDot>>();
  select_layers(data, style, *map, *labels, *dots);
  auto channel = [](double c) { return uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255)); };
  map->background = {channel(style.background.r), channel(style.background.g),
                     channel(style.background.b)};
  map->scale = double(1 << kVectorMapDetail);
  return {map, labels, dots, width, height, frame};
}

}  // namespace

std::vector<MapLabel> vector_map_labels(const VectorData& data, const MapStyle& style, int width,
                                        int height) {
  return *build_map(data, style, width, height, "vector_map_labels").labels;
}

SourceFile vector_map_source(const VectorData& data, const MapStyle& style, int width, int height) {
  // Named one by one: clang 14 (the fuzz build's, scripts/fuzz.sh) cannot capture the names of a
  // structured binding.
  const BuiltMap built = build_map(data, style, width, height, "vector_map_source");
  const std::shared_ptr<MapData>& map = built.map;
  const std::shared_ptr<std::vector<MapLabel>>& labels = built.labels;
  const std::shared_ptr<std::vector<MapDot>>& dots = built.dots;
  const int frame_width = built.width, frame_height = built.height;

  auto source = std::make_shared<TiledSource>(
      int(frame_width * map->scale), int(frame_height * map->scale), 3,
      [map](const TileRequest& request) { return draw_tile(*map, request); });
  auto placed_count = std::make_shared<std::atomic<size_t>>(0);

  SourceFile file;
  file.frame_width = frame_width;
  file.frame_height = frame_height;
  file.scale = map->scale;
  file.kind = "vector map";
  file.map_frame = built.frame;
  // Each zoom is drawn on its own (labels, line widths): blended only about their midpoint.
  file.level_band = 0.25;
  const size_t feature_count = data.features.size();
  file.counters = [source, placed_count, feature_count]() {
    const TileCacheStats stats = source->cache_stats();
    return std::vector<std::pair<std::string, double>>{
        {"tiles", double(stats.tiles_made)},
        {"cache_peak_mb", double(stats.peak_bytes) / (1 << 20)},
        {"labels", double(placed_count->load())},
        {"features", double(feature_count)}};
  };
  if (!labels->empty() || !dots->empty())
    file.overlay = [labels, dots, placed_count](Image& output, const WarpMap& warp) {
      draw_dots(output, *dots, warp);
      const std::vector<PlacedLabel> placed =
          place_labels(*labels, warp, output.width, output.height);
      draw_labels(output, *labels, placed);
      placed_count->store(placed.size());
    };
  file.source = std::move(source);
  return file;
}

SourceFile open_vector_map(const std::string& path, const SourceFileOptions& options) {
  const MapStyle style =
      options.style.empty() ? default_map_style() : read_map_style(options.style);
  const VectorData data = read_geojson(path, options.max_points);
  try {
    return vector_map_source(data, style, options.width, options.height);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("open_vector_map: '") + path + "': " + e.what());
  }
}

}  // namespace geolens
