#include "geolens/io/geojson.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"

namespace geolens {

namespace {

// Objects keep their key order, so properties pass through as they were.
using Json = nlohmann::ordered_json;

// A nlohmann message without its "[json.exception.parse_error.101] " prefix.
std::string plain(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  const size_t end = what.find("] ");
  return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2)
                                                                            : what;
}

// A JSON value as text for a message, cut to 40 characters.
std::string excerpt(const Json& j) {
  const std::string text = j.dump();
  return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

std::optional<GeometryType> geometry_type(const std::string& name) {
  for (GeometryType t : {GeometryType::kPoint, GeometryType::kMultiPoint, GeometryType::kLineString,
                         GeometryType::kMultiLineString, GeometryType::kPolygon,
                         GeometryType::kMultiPolygon, GeometryType::kGeometryCollection})
    if (to_string(t) == name) return t;
  return std::nullopt;
}

// Builds the model from the JSON tree; every failure names the document and where in it.
class Reader {
 public:
  Reader(std::string name, size_t max_points) : name_(std::move(name)), max_points_(max_points) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InvalidInput("parse_geojson: '" + name_ + "': " + where + ": " + what);
  }

  // The "type" member of an object.
  std::string type(const Json& j, const std::string& where) const {
    if (!j.is_object()) fail(where, "expected an object, got " + std::string(j.type_name()));
    const auto t = j.find("type");
    if (t == j.end() || !t->is_string()) fail(where, "has no \"type\" string");
    return t->get<std::string>();
  }

  // The array member `key` of the object j.
  const Json& array(const Json& j, const char* key, const std::string& where) const {
    const auto a = j.find(key);
    if (a == j.end()) fail(where, std::string("has no \"") + key + "\" member");
    if (!a->is_array())
      fail(where, std::string("\"") + key + "\" is " + a->type_name() + ", not an array");
    return *a;
  }

  // Counts one more position read, refusing more than max_points in all.
  void count_position(const std::string& where) {
    if (++points_ > max_points_)
      fail(where, "more than the " + std::to_string(max_points_) +
                      " positions read in all (max_points; --max-points raises it)");
  }

  Eigen::RowVector2d position(const Json& j, const std::string& where) {
    count_position(where);
    if (!j.is_array() || j.size() != 2 || !j[0].is_number() || !j[1].is_number())
      fail(where, "expected a position [x, y] of two numbers, got " + excerpt(j) +
                      (j.is_array() && j.size() > 2 ? " (altitude is not supported)" : ""));
    const Eigen::RowVector2d p(j[0].get<double>(), j[1].get<double>());
    if (!p.allFinite()) fail(where, "the position " + excerpt(j) + " is not finite");
    return p;
  }

  Eigen::MatrixX2d positions(const Json& j, const std::string& where) {
    if (!j.is_array()) fail(where, "expected an array of positions, got " + excerpt(j));
    Eigen::MatrixX2d P(Eigen::Index(j.size()), 2);
    for (size_t k = 0; k < j.size(); ++k)
      P.row(Eigen::Index(k)) = position(j[k], where + "[" + std::to_string(k) + "]");
    return P;
  }

  Geometry geometry(const Json& j, const std::string& where) {
    const std::string name = type(j, where);
    const std::optional<GeometryType> type_named = geometry_type(name);
    if (!type_named) fail(where, "unknown geometry type \"" + name + "\"");
    Geometry g;
    g.type = *type_named;
    if (g.type == GeometryType::kGeometryCollection) {
      const Json& members = array(j, "geometries", where);
      for (size_t k = 0; k < members.size(); ++k)
        g.members.push_back(geometry(
            members[k], where + " GeometryCollection geometries[" + std::to_string(k) + "]"));
    } else {
      const Json& c = array(j, "coordinates", where);
      const std::string at = where + " " + name + " coordinates";
      auto nested = [&](size_t k) { return at + "[" + std::to_string(k) + "]"; };
      switch (g.type) {
        case GeometryType::kPoint:
          g.paths.push_back(position(c, at));
          break;
        case GeometryType::kMultiPoint:
        case GeometryType::kLineString:
          g.paths.push_back(positions(c, at));
          break;
        case GeometryType::kMultiLineString:
        case GeometryType::kPolygon:
          for (size_t k = 0; k < c.size(); ++k) g.paths.push_back(positions(c[k], nested(k)));
          break;
        case GeometryType::kMultiPolygon:
          for (size_t p = 0; p < c.size(); ++p) {
            if (!c[p].is_array())
              fail(nested(p), "expected an array of rings, got " + excerpt(c[p]));
            g.rings.push_back(int(c[p].size()));
            for (size_t k = 0; k < c[p].size(); ++k)
              g.paths.push_back(positions(c[p][k], nested(p) + "[" + std::to_string(k) + "]"));
          }
          break;
        case GeometryType::kGeometryCollection:
          break;
      }
    }
    const std::string problem = geometry_problem(g);
    if (!problem.empty()) fail(where, problem);
    return g;
  }

  Feature feature(const Json& j, const std::string& where) {
    const std::string name = type(j, where);
    if (name != "Feature") fail(where, "expected a Feature, got \"" + name + "\"");
    Feature f;
    const auto g = j.find("geometry");
    if (g == j.end()) fail(where, "has no \"geometry\" member (null for none)");
    if (!g->is_null()) f.geometry = geometry(*g, where);
    const auto properties = j.find("properties");
    if (properties != j.end()) {
      if (!properties->is_object() && !properties->is_null())
        fail(where, std::string("\"properties\" is ") + properties->type_name() +
                        ", not an object or null");
      f.properties = properties->dump();
    }
    const auto id = j.find("id");
    if (id != j.end()) {
      if (!id->is_string() && !id->is_number())
        fail(where, std::string("\"id\" is ") + id->type_name() + ", not a string or number");
      f.id = id->dump();
    }
    return f;
  }

  VectorData document(const std::string& text) {
    if (const size_t depth = json_depth(text); depth > kMaxJsonDepth)
      fail("the document", "nested " + std::to_string(depth) + " levels deep; at most " +
                               std::to_string(kMaxJsonDepth) + " are read");
    Json root;
    try {
      root = Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      fail("not JSON", plain(e));
    }
    VectorData data;
    const std::string name = type(root, "the document");
    if (name == "FeatureCollection") {
      const Json& features = array(root, "features", "the FeatureCollection");
      for (size_t k = 0; k < features.size(); ++k)
        data.features.push_back(feature(features[k], "feature " + std::to_string(k)));
    } else if (name == "Feature") {
      data.root = GeoJsonRoot::kFeature;
      data.features.push_back(feature(root, "feature 0"));
    } else {
      data.root = GeoJsonRoot::kGeometry;
      data.features.push_back({geometry(root, "the geometry"), "", "null"});
    }
    return data;
  }

 private:
  std::string name_;
  size_t max_points_, points_ = 0;
};

Json position_json(const Eigen::MatrixX2d& P, Eigen::Index i) {
  return Json::array({P(i, 0), P(i, 1)});
}

Json path_json(const Eigen::MatrixX2d& P) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < P.rows(); ++i) a.push_back(position_json(P, i));
  return a;
}

Json geometry_json(const Geometry& g) {
  Json j = {{"type", to_string(g.type)}};
  if (g.type == GeometryType::kGeometryCollection) {
    Json members = Json::array();
    for (const Geometry& m : g.members) members.push_back(geometry_json(m));
    j["geometries"] = std::move(members);
    return j;
  }
  Json c = Json::array();
  switch (g.type) {
    case GeometryType::kPoint:
      c = position_json(g.paths[0], 0);
      break;
    case GeometryType::kMultiPoint:
    case GeometryType::kLineString:
      c = path_json(g.paths[0]);
      break;
    case GeometryType::kMultiLineString:
    case GeometryType::kPolygon:
      for (const Eigen::MatrixX2d& P : g.paths) c.push_back(path_json(P));
      break;
    case GeometryType::kMultiPolygon: {
      size_t next = 0;
      for (const int rings : g.rings) {
        Json polygon = Json::array();
        for (int k = 0; k < rings; ++k) polygon.push_back(path_json(g.paths[next++]));
        c.push_back(std::move(polygon));
      }
      break;
    }
    case GeometryType::kGeometryCollection:
      break;
  }
  j["coordinates"] = std::move(c);
  return j;
}

// The JSON text `text` of a feature's id or properties, parsed back.
Json member_json(const std::string& text, size_t feature, const char* member) {
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput("geojson_text: feature " + std::to_string(feature) + ": " + member +
                       " is not JSON: " + plain(e));
  }
}

Json feature_json(const Feature& f, size_t k) {
  Json j = {{"type", "Feature"}};
  if (!f.id.empty()) j["id"] = member_json(f.id, k, "id");
  j["geometry"] = f.geometry ? geometry_json(*f.geometry) : Json(nullptr);
  j["properties"] = member_json(f.properties, k, "properties");
  return j;
}

}  // namespace

size_t json_depth(const std::string& text) {
  size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

size_t geojson_bytes_limit(size_t max_points) {
  return std::max(kMaxGeoJsonBytes, std::min(max_points, size_t(1) << 36) * 16);
}

VectorData parse_geojson(const std::string& text, const std::string& name, size_t max_points) {
  require(max_points >= 1, "parse_geojson", "max_points must be >= 1, got 0");
  require(text.size() <= geojson_bytes_limit(max_points), "parse_geojson",
          "'" + name + "' is larger than the " +
              std::to_string(geojson_bytes_limit(max_points) >> 20) +
              " MiB a GeoJSON text may hold (16 bytes a position of max_points, at least 64 MiB)");
  return Reader(name, max_points).document(text);
}

VectorData read_geojson(const std::string& path, size_t max_points) {
  require(max_points >= 1, "read_geojson", "max_points must be >= 1, got 0");
  return parse_geojson(read_file(path, "read_geojson", "GeoJSON", geojson_bytes_limit(max_points)),
                       path, max_points);
}

std::string geojson_text(const VectorData& data) {
  const std::string problem = vector_data_problem(data);
  require(problem.empty(), "geojson_text", problem);
  switch (data.root) {
    case GeoJsonRoot::kGeometry: {
      const Feature& f = data.features[0];
      return (f.geometry ? geometry_json(*f.geometry)
                         : Json{{"type", "GeometryCollection"}, {"geometries", Json::array()}})
                 .dump() +
             "\n";
    }
    case GeoJsonRoot::kFeature:
      return feature_json(data.features[0], 0).dump() + "\n";
    case GeoJsonRoot::kFeatureCollection:
      break;
  }
  std::string text = "{\"type\":\"FeatureCollection\",\"features\":[";
  for (size_t k = 0; k < data.features.size(); ++k)
    text += (k == 0 ? "\n" : ",\n") + feature_json(data.features[k], k).dump();
  return text + (data.features.empty() ? "]}\n" : "\n]}\n");
}

std::optional<std::string> string_property(const Feature& feature, const std::string& key) {
  const Json properties = Json::parse(feature.properties, nullptr, false);
  if (!properties.is_object()) return std::nullopt;
  const auto value = properties.find(key);
  if (value == properties.end() || !value->is_string()) return std::nullopt;
  return value->get<std::string>();
}

}  // namespace geolens
