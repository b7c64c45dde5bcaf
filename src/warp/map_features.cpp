#include "geolens/warp/map_features.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "warp/densify.h"

namespace geolens {

namespace {

constexpr int kBisections = 40;  // the border of the covered area to 2^-40 of a segment

std::optional<Eigen::Vector2d> map_point(const WarpMap& map, MapDirection direction,
                                         const Eigen::Vector2d& p) {
  return direction == MapDirection::kForward ? map.forward(p) : map.inverse(p);
}

// Appends `piece` to `pieces` as a #P x 2 path if it has at least 2 vertices, and empties it.
void end_piece(std::vector<Eigen::Vector2d>& piece, std::vector<Eigen::MatrixX2d>& pieces) {
  if (piece.size() >= 2) {
    Eigen::MatrixX2d P(Eigen::Index(piece.size()), 2);
    for (size_t k = 0; k < piece.size(); ++k) P.row(Eigen::Index(k)) = piece[k].transpose();
    pieces.push_back(std::move(P));
  }
  piece.clear();
}

// Maps the parts of geometries one way through a WarpMap and counts what it leaves out.
class Mapper {
 public:
  Mapper(const WarpMap& map, const MapOptions& options) : map_(map), options_(options) {
    // The covered area's bounding box, grown by a pixel: nothing beyond it maps.
    const Eigen::MatrixX2d& side =
        options.direction == MapDirection::kForward ? map.mesh().source : map.mesh().screen;
    box_ = Eigen::AlignedBox2d(side.colwise().minCoeff().transpose(),
                               side.colwise().maxCoeff().transpose());
    box_.min().array() -= 1;
    box_.max().array() += 1;
  }

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
          bool lost = false;
          for (const Eigen::MatrixX2d& part : clipped(line, lost))
            for (Eigen::MatrixX2d& piece : cut(densified(part), lost))
              out.paths.push_back(std::move(piece));
          lost_.lines += lost;
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

  // `path` densified, its rows counted against kMaxDensifiedRows for all the features.
  Eigen::MatrixX2d densified(const Eigen::MatrixX2d& path) {
    Eigen::MatrixX2d out = densify(path, options_.max_segment);
    rows_ += out.rows();
    require_option(rows_ <= kMaxDensifiedRows, "map_features", "max_segment",
                   number_text(options_.max_segment) + " px makes more than " +
                       std::to_string(kMaxDensifiedRows) +
                       " vertices of the lines and rings in all: take a larger one");
    return out;
  }

  // The parts of `line` within box_, its vertices there kept exactly, a part's first and last
  // vertex on the box's edge where the line crosses it; `lost` set if anything was left out.
  // What lies beyond is cut anyway; a vertex at x = 1e300 made densify and the border search
  // work on the whole segment (refused: more than 2^24 vertices).
  std::vector<Eigen::MatrixX2d> clipped(const Eigen::MatrixX2d& line, bool& lost) const {
    std::vector<Eigen::MatrixX2d> parts;
    std::vector<Eigen::Vector2d> part;
    auto close = [&] { end_piece(part, parts); };
    for (Eigen::Index i = 0; i + 1 < line.rows(); ++i) {
      const Eigen::Vector2d a = line.row(i).transpose(), b = line.row(i + 1).transpose();
      // Liang-Barsky: the parameters [t0, t1] of a + t (b - a) inside the box.
      double t0 = 0, t1 = 1;
      const Eigen::Vector2d d = b - a;
      bool inside = true;
      for (int axis = 0; axis < 2 && inside; ++axis) {
        const double low = box_.min()[axis] - a[axis], high = box_.max()[axis] - a[axis];
        if (d[axis] == 0) {
          inside = low <= 0 && high >= 0;
          continue;
        }
        const double ta = low / d[axis], tb = high / d[axis];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
        inside = t0 <= t1;
      }
      if (!inside) {
        lost = true;
        close();
        continue;
      }
      if (part.empty() || t0 > 0) {
        close();
        part.push_back(t0 > 0 ? Eigen::Vector2d(a + t0 * d) : a);
      }
      part.push_back(t1 < 1 ? Eigen::Vector2d(a + t1 * d) : b);
      if (t0 > 0 || t1 < 1) lost = true;
      if (t1 < 1) close();
    }
    close();
    return parts;
  }

  // The pieces of the (densified) line inside the covered area, mapped, each ending on the
  // area's border where the line leaves it; pieces of fewer than 2 vertices left out. Sets
  // `lost` if any vertex is outside.
  std::vector<Eigen::MatrixX2d> cut(const Eigen::MatrixX2d& line, bool& lost) {
    std::vector<Eigen::MatrixX2d> pieces;
    std::vector<Eigen::Vector2d> piece;
    auto close = [&] { end_piece(piece, pieces); };
    std::optional<Eigen::Vector2d> previous;
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
    return pieces;
  }

  // Appends to out.paths the rings paths[first, first + count), densified and mapped, if every
  // vertex maps; otherwise counts a dropped polygon and appends nothing.
  bool polygon(const std::vector<Eigen::MatrixX2d>& paths, size_t first, size_t count,
               Geometry& out) {
    std::vector<Eigen::MatrixX2d> rings;
    for (size_t k = first; k < first + count; ++k) {
      const Eigen::MatrixX2d ring = densified(paths[k]);
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
  Eigen::AlignedBox2d box_;
  Eigen::Index rows_ = 0;  // densified so far
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
