#include "geolens/source/map_style.h"

#include <cctype>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "geolens/io/geojson.h"

namespace geolens {

namespace {

// The largest width, radius or font size a style may give, pixels: a radius of 1e300 hung the
// renderer, a huge width filled the frame at any zoom.
constexpr double kMaxStylePixels = 1000;
constexpr size_t kMaxStyleBytes = size_t(16) << 20;  ///< a style is a few KB of JSON

using Json = nlohmann::json;

// Reads the style tree; every failure names the document and the key path at fault.
class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InvalidInput("map_style: '" + name_ + "': " + where + ": " + what);
  }

  // Refuses a member of the object j at `where` that is not in `known`.
  void only(const Json& j, const std::string& where, const std::set<std::string>& known) const {
    if (!j.is_object())
      fail(where.empty() ? "document" : where,
           std::string("expected an object, got ") + j.type_name());
    for (const auto& [key, value] : j.items())
      if (!known.count(key)) fail(join(where, key), "unknown key");
  }

  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

  MapColor color(const Json& j, const std::string& where) const {
    const std::string text = j.is_string() ? j.get<std::string>() : j.dump();
    auto bad = [&]() {
      fail(where, "'" + text + "' is not a colour (#rgb, #rrggbb or #rrggbbaa)");
    };
    if (!j.is_string() || text.empty() || text[0] != '#') bad();
    const std::string hex = text.substr(1);
    for (char c : hex)
      if (!std::isxdigit(static_cast<unsigned char>(c))) bad();
    std::vector<int> v;
    if (hex.size() == 3) {
      for (char c : hex) v.push_back(std::stoi(std::string(2, c), nullptr, 16));
    } else if (hex.size() == 6 || hex.size() == 8) {
      for (size_t i = 0; i < hex.size(); i += 2)
        v.push_back(std::stoi(hex.substr(i, 2), nullptr, 16));
    } else {
      bad();
    }
    return {v[0] / 255.0, v[1] / 255.0, v[2] / 255.0, v.size() == 4 ? v[3] / 255.0 : 1.0};
  }

  double number(const Json& j, const std::string& where, double min,
                double max = std::numeric_limits<double>::max()) const {
    if (!j.is_number()) fail(where, "'" + j.dump() + "' is not a number");
    const double value = j.get<double>();
    if (!std::isfinite(value) || value < min || value > max)
      fail(where, j.dump() + " is out of range (at least " + Json(min).dump() +
                      (max < std::numeric_limits<double>::max() ? ", at most " + Json(max).dump()
                                                                : std::string()) +
                      ")");
    return value;
  }

  std::string string(const Json& j, const std::string& where) const {
    if (!j.is_string() || j.get<std::string>().empty())
      fail(where, "'" + j.dump() + "' is not a non-empty string");
    return j.get<std::string>();
  }

  MapLabelStyle label(const Json& j, const std::string& where) const {
    only(j, where, {"text", "rank", "base", "size", "color", "halo", "halo_width"});
    MapLabelStyle l;
    for (const auto& [key, value] : j.items()) {
      const std::string at = join(where, key);
      if (key == "text") {
        l.text.clear();
        if (value.is_array()) {
          if (value.empty()) fail(at, "the list is empty");
          for (size_t i = 0; i < value.size(); ++i)
            l.text.push_back(string(value[i], at + "[" + std::to_string(i) + "]"));
        } else {
          l.text.push_back(string(value, at));
        }
      } else if (key == "rank") {
        l.rank = string(value, at);
      } else if (key == "base") {
        l.base = number(value, at, -1e9);
      } else if (key == "size") {
        l.size = number(value, at, 1, kMaxStylePixels);
      } else if (key == "color") {
        l.color = color(value, at);
      } else if (key == "halo") {
        l.halo = color(value, at);
      } else if (key == "halo_width") {
        l.halo_width = number(value, at, 0, kMaxStylePixels);
      }
    }
    return l;
  }

  MapLayerStyle layer(const Json& j, const std::string& where) const {
    only(j, where,
         {"name", "where", "geometry", "fill", "stroke", "width", "radius", "min_zoom", "max_zoom",
          "label"});
    MapLayerStyle l;
    l.name = where;
    for (const auto& [key, value] : j.items()) {
      const std::string at = join(where, key);
      if (key == "name") {
        l.name = string(value, at);
      } else if (key == "where") {
        if (!value.is_object())
          fail(at, std::string("expected an object, got ") + value.type_name());
        for (const auto& [property, wanted] : value.items()) {
          MapLayerStyle::Condition c{property, {}};
          const Json list = wanted.is_array() ? wanted : Json::array({wanted});
          if (list.empty()) fail(join(at, property), "the list is empty");
          for (const Json& v : list) {
            if (!v.is_primitive() || v.is_null())
              fail(join(at, property), "'" + v.dump() + "' is not a string, number or boolean");
            c.values.push_back(v.dump());
          }
          l.where.push_back(std::move(c));
        }
      } else if (key == "geometry") {
        const std::string g = value.is_string() ? value.get<std::string>() : value.dump();
        using G = MapLayerStyle::Geometry;
        if (g == "any")
          l.geometry = G::kAny;
        else if (g == "point")
          l.geometry = G::kPoint;
        else if (g == "line")
          l.geometry = G::kLine;
        else if (g == "polygon")
          l.geometry = G::kPolygon;
        else
          fail(at, "'" + g + "' is not any, point, line or polygon");
      } else if (key == "fill") {
        l.fill = color(value, at);
      } else if (key == "stroke") {
        l.stroke = color(value, at);
      } else if (key == "width") {
        l.width = number(value, at, 0, kMaxStylePixels);
      } else if (key == "radius") {
        l.radius = number(value, at, 0, kMaxStylePixels);
      } else if (key == "min_zoom") {
        l.min_zoom = number(value, at, 0);
      } else if (key == "max_zoom") {
        l.max_zoom = number(value, at, 0);
      } else if (key == "label") {
        l.label = label(value, at);
      }
    }
    if (l.min_zoom > l.max_zoom)
      fail(where,
           "min_zoom " + Json(l.min_zoom).dump() + " is above max_zoom " + Json(l.max_zoom).dump());
    return l;
  }

  MapStyle style(const Json& j) const {
    only(j, "", {"background", "projection", "extent", "layers"});
    MapStyle s = default_map_style();
    for (const auto& [key, value] : j.items()) {
      if (key == "background") {
        s.background = color(value, key);
      } else if (key == "projection") {
        const std::string p = value.is_string() ? value.get<std::string>() : value.dump();
        if (p == "web_mercator")
          s.projection = MapProjection::kWebMercator;
        else if (p == "plate_carree")
          s.projection = MapProjection::kPlateCarree;
        else
          fail(key, "'" + p + "' is not web_mercator or plate_carree");
      } else if (key == "extent") {
        if (!value.is_array() || value.size() != 4)
          fail(key, "expected [west, south, east, north], got " + value.dump());
        std::array<double, 4> e;
        for (int i = 0; i < 4; ++i)
          e[i] = number(value[i], key + "[" + std::to_string(i) + "]", -1e9);
        if (!(e[0] >= -180 && e[0] < e[2] && e[2] <= 180 && e[1] >= -90 && e[1] < e[3] &&
              e[3] <= 90))
          fail(key, value.dump() +
                        " is not [west, south, east, north] with west < east in "
                        "[-180, 180] and south < north in [-90, 90]");
        s.extent = e;
      } else if (key == "layers") {
        if (!value.is_array()) fail(key, std::string("expected a list, got ") + value.type_name());
        s.layers.clear();
        for (size_t i = 0; i < value.size(); ++i)
          s.layers.push_back(layer(value[i], "layers[" + std::to_string(i) + "]"));
      }
    }
    return s;
  }

 private:
  std::string name_;
};

}  // namespace

MapStyle default_map_style() {
  using G = MapLayerStyle::Geometry;
  const MapColor grey{0.45, 0.45, 0.45, 1};
  MapStyle style;
  MapLayerStyle areas;
  areas.name = "areas";
  areas.geometry = G::kPolygon;
  areas.fill = MapColor{0.96, 0.94, 0.89, 1};
  areas.stroke = grey;
  MapLayerStyle lines;
  lines.name = "lines";
  lines.geometry = G::kLine;
  lines.stroke = grey;
  MapLayerStyle points;
  points.name = "points";
  points.geometry = G::kPoint;
  points.fill = MapColor{0.2, 0.2, 0.2, 1};
  points.stroke = MapColor{1, 1, 1, 1};
  points.width = 0.8;
  points.radius = 2;
  points.label = MapLabelStyle{};
  style.layers = {areas, lines, points};
  return style;
}

MapStyle parse_map_style(const std::string& text, const std::string& name) {
  const Reader reader(name);
  if (const size_t depth = json_depth(text); depth > kMaxJsonDepth)
    reader.fail("JSON", "nested " + std::to_string(depth) + " levels deep; at most " +
                            std::to_string(kMaxJsonDepth) + " are read");
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {  // a syntax error, or a number past a double (1e999)
    const std::string what = e.what();
    const size_t end = what.find("] ");
    reader.fail("JSON", end == std::string::npos ? what : what.substr(end + 2));
  }
  return reader.style(j);
}

MapStyle read_map_style(const std::string& path) {
  return parse_map_style(read_file(path, "read_map_style", "style", kMaxStyleBytes), path);
}

}  // namespace geolens
