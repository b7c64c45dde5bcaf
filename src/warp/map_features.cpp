#include "geolens/warp/map_features.h"

#include <optional>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/warp/densify.h"

namespace geolens {

namespace {

constexpr int kBisections = 40;  // the border of the covered area to 2^-40 of a segment

std::optional<Eigen::Vector2d> map_point(const WarpMap& map, MapDirection direction,
                                         const Eigen::Vector2d& p) {
  return direction == MapDirection::kForward ? map.forward(p) : map.inverse(p);
}

// Maps the parts of geometries one way through a WarpMap and counts what it leaves out.
class Mapper {
 public:
  Mapper(const WarpMap& map, const MapOptions& options) : map_(map), options_(options) {}

  // The geometry mapped, or empty when nothing of it is left.
  std::optional<Geometry> geometry(const Geometry& g) {
    Geometry out;
    out.type = g.type;
    switch (g.type) {
      case GeometryType::kPoint:
      case GeometryType::kMultiPoint:
        out.paths.push_back(points(g.paths[0]));
        if (out.paths[0].rows() == 0) return std::nullopt;
        return out;
      case GeometryType::kLineString:
      case GeometryType::kMultiLineString:
        for (const Eigen::MatrixX2d& line : g.paths) {
          for (Eigen::MatrixX2d& piece : cut(densify(line, options_.max_segment)))
            out.paths.push_back(std::move(piece));
        }
        if (out.paths.empty()) return std::nullopt;
        if (out.paths.size() > 1) out.type = GeometryType::kMultiLineString;
        return out;
      case GeometryType::kPolygon:
        if (!polygon(g.paths, 0, g.paths.size(), out) || out.paths.empty()) return std::nullopt;
        return out;
      case GeometryType::kMultiPolygon: {
        size_t first = 0;
        for (const int rings : g.rings) {
          if (polygon(g.paths, first, size_t(rings), out)) out.rings.push_back(rings);
          first += size_t(rings);
        }
        if (out.rings.empty()) return std::nullopt;
        return out;
      }
      case GeometryType::kGeometryCollection:
        for (const Geometry& member : g.members)
          if (std::optional<Geometry> m = geometry(member)) out.members.push_back(std::move(*m));
        if (out.members.empty()) return std::nullopt;
        return out;
    }
    return std::nullopt;
  }

  const MapLosses& losses() const { return lost_; }

 private:
  std::optional<Eigen::Vector2d> at(const Eigen::Vector2d& p) const {
    return map_point(map_, options_.direction, p);
  }

  // The rows of P that map, mapped, in order.
  Eigen::MatrixX2d points(const Eigen::MatrixX2d& P) {
    Eigen::MatrixX2d out(P.rows(), 2);
    Eigen::Index kept = 0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      if (const std::optional<Eigen::Vector2d> q = at(P.row(i).transpose()))
        out.row(kept++) = q->transpose();
      else
        ++lost_.points;
    }
    out.conservativeResize(kept, 2);
    return out;
  }

  // The image of the last covered point on the segment from `in` (covered) to `out` (not).
  Eigen::Vector2d border(const Eigen::Vector2d& in, const Eigen::Vector2d& out,
                         const Eigen::Vector2d& in_image) const {
    double lo = 0, hi = 1;
    Eigen::Vector2d image = in_image;
    for (int k = 0; k < kBisections; ++k) {
      const double mid = (lo + hi) / 2;
      if (const std::optional<Eigen::Vector2d> q = at(in + mid * (out - in))) {
        lo = mid;
        image = *q;
      } else {
        hi = mid;
      }
    }
    return image;
  }

  // The pieces of the (densified) line inside the covered area, mapped, each ending on the
  // area's border where the line leaves it; pieces of fewer than 2 vertices left out. Counts
  // the line as lost if any vertex is outside.
  std::vector<Eigen::MatrixX2d> cut(const Eigen::MatrixX2d& line) {
    std::vector<Eigen::MatrixX2d> pieces;
    std::vector<Eigen::Vector2d> piece;
    auto close = [&] {
      if (piece.size() >= 2) {
        Eigen::MatrixX2d P(Eigen::Index(piece.size()), 2);
        for (size_t k = 0; k < piece.size(); ++k) P.row(Eigen::Index(k)) = piece[k].transpose();
        pieces.push_back(std::move(P));
      }
      piece.clear();
    };
    std::optional<Eigen::Vector2d> previous;
    bool lost = false;
    for (Eigen::Index i = 0; i < line.rows(); ++i) {
      const Eigen::Vector2d p = line.row(i).transpose();
      const std::optional<Eigen::Vector2d> q = at(p);
      if (i > 0 && q.has_value() != previous.has_value()) {
        const Eigen::Vector2d before = line.row(i - 1).transpose();
        if (q) {
          piece.push_back(border(p, before, *q));  // entering: the piece starts on the border
        } else {
          piece.push_back(border(before, p, *previous));  // leaving: it ends there
          close();
        }
      }
      if (q) piece.push_back(*q);
      previous = q;
      lost = lost || !q;
    }
    close();
    lost_.lines += lost;
    return pieces;
  }

  // Appends to out.paths the rings paths[first, first + count), densified and mapped, if every
  // vertex maps; otherwise counts a dropped polygon and appends nothing.
  bool polygon(const std::vector<Eigen::MatrixX2d>& paths, size_t first, size_t count,
               Geometry& out) {
    std::vector<Eigen::MatrixX2d> rings;
    for (size_t k = first; k < first + count; ++k) {
      const Eigen::MatrixX2d ring = densify(paths[k], options_.max_segment);
      Eigen::MatrixX2d mapped(ring.rows(), 2);
      for (Eigen::Index i = 0; i < ring.rows(); ++i) {
        const std::optional<Eigen::Vector2d> q = at(ring.row(i).transpose());
        if (!q) {
          ++lost_.polygons;
          return false;
        }
        mapped.row(i) = q->transpose();
      }
      rings.push_back(std::move(mapped));
    }
    for (Eigen::MatrixX2d& ring : rings) out.paths.push_back(std::move(ring));
    return true;
  }

  const WarpMap& map_;
  MapOptions options_;
  MapLosses lost_;
};

}  // namespace

MappedFeatures map_features(const VectorData& data, const WarpMap& map, const MapOptions& options) {
  require(options.max_segment > 0, "map_features",
          "max_segment must be > 0 pixels, got " + number_text(options.max_segment));
  const std::string problem = vector_data_problem(data);
  require(problem.empty(), "map_features", problem);
  Mapper mapper(map, options);
  MappedFeatures result;
  result.data.root = data.root;
  for (const Feature& f : data.features) {
    Feature mapped{std::nullopt, f.id, f.properties};
    if (f.geometry) mapped.geometry = mapper.geometry(*f.geometry);
    result.data.features.push_back(std::move(mapped));
  }
  result.losses = mapper.losses();
  return result;
}

MappedPoints map_points(const PointTable& table, const WarpMap& map, MapDirection direction) {
  require(table.rest.size() == size_t(table.points.rows()), "map_points",
          "rest has " + std::to_string(table.rest.size()) + " rows for " +
              std::to_string(table.points.rows()) + " points");
  for (Eigen::Index i = 0; i < table.points.rows(); ++i)
    require(table.points.row(i).allFinite(), "map_points",
            "point " + std::to_string(i) + " is not finite");
  MappedPoints result;
  result.table.header = table.header;
  result.table.points.resize(table.points.rows(), 2);
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < table.points.rows(); ++i) {
    const std::optional<Eigen::Vector2d> q =
        map_point(map, direction, table.points.row(i).transpose());
    if (!q) {
      ++result.losses.points;
      continue;
    }
    result.table.points.row(kept++) = q->transpose();
    result.table.rest.push_back(table.rest[size_t(i)]);
  }
  result.table.points.conservativeResize(kept, 2);
  return result;
}

}  // namespace geolens
