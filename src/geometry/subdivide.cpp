#include "geolens/geometry/subdivide.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {

namespace {

uint64_t edge_key(int a, int b) {
  return (uint64_t(std::min(a, b)) << 32) | uint64_t(std::max(a, b));
}

// Longest-edge bisection with propagation (Rivara's LEPP refinement): a triangle is split at the
// midpoint of its longest planar edge together with the neighbour across it, after the neighbour
// has itself been split until that edge is its longest too. The mesh stays conforming, and on the
// grid's right isosceles triangles every child is again right isosceles: no angle degrades.
class Bisector {
 public:
  Bisector(PlanarMesh& mesh, std::vector<double>& z,
           const std::function<double(const Eigen::Vector2d&)>& height)
      : mesh_(mesh), z_(z), height_(height) {
    faces_.resize(size_t(mesh.F.rows()));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      faces_[size_t(f)] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
      attach(int(f));
    }
    stamp_.assign(faces_.size(), -1);
    vertices_.reserve(size_t(mesh.V.rows()) * 2);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) vertices_.push_back(mesh.V.row(i));
  }

  // Refines every marked triangle once; triangles created in this round are not refined again.
  void refine(const std::vector<int>& marked, int round) {
    round_ = round;
    for (int f : marked)
      if (stamp_[size_t(f)] != round) bisect(f);
  }

  size_t face_count() const { return faces_.size(); }
  const std::array<int, 3>& face(size_t f) const { return faces_[f]; }
  Eigen::Vector2d vertex(int i) const { return vertices_[size_t(i)]; }

  void write_back() {
    mesh_.V.resize(Eigen::Index(vertices_.size()), 2);
    for (size_t i = 0; i < vertices_.size(); ++i) mesh_.V.row(Eigen::Index(i)) = vertices_[i];
    mesh_.F.resize(Eigen::Index(faces_.size()), 3);
    for (size_t f = 0; f < faces_.size(); ++f)
      mesh_.F.row(Eigen::Index(f)) << faces_[f][0], faces_[f][1], faces_[f][2];
  }

 private:
  // Index k of the longest edge (faces_[f][k], faces_[f][k + 1]); ties go to the smaller key so
  // both triangles of an edge agree.
  int longest(int f) const {
    const auto& t = faces_[size_t(f)];
    int best = 0;
    double best_length = -1;
    uint64_t best_key = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      const double length = (vertices_[size_t(a)] - vertices_[size_t(b)]).squaredNorm();
      const uint64_t key = edge_key(a, b);
      if (length > best_length * (1 + 1e-12) ||
          (length >= best_length * (1 - 1e-12) && key < best_key)) {
        best = k;
        best_length = length;
        best_key = key;
      }
    }
    return best;
  }

  int neighbour(int f, int a, int b) const {
    const auto& pair = edges_.at(edge_key(a, b));
    return pair[0] == f ? pair[1] : pair[0];
  }

  void attach(int f) {
    const auto& t = faces_[size_t(f)];
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = edges_.try_emplace(edge_key(t[size_t(k)], t[size_t((k + 1) % 3)]),
                                               std::array<int, 2>{f, -1});
      if (!inserted) (it->second[0] == -1 ? it->second[0] : it->second[1]) = f;
    }
  }

  void detach(int f) {
    const auto& t = faces_[size_t(f)];
    for (int k = 0; k < 3; ++k) {
      const auto it = edges_.find(edge_key(t[size_t(k)], t[size_t((k + 1) % 3)]));
      if (it == edges_.end()) continue;  // the split edge, already removed by the neighbour
      (it->second[0] == f ? it->second[0] : it->second[1]) = -1;
    }
  }

  void bisect(int f) {
    for (;;) {
      const int k = longest(f);
      const int a = faces_[size_t(f)][size_t(k)], b = faces_[size_t(f)][size_t((k + 1) % 3)];
      const int n = neighbour(f, a, b);
      if (n >= 0) {
        const auto& u = faces_[size_t(n)];
        const int kn = longest(n);
        if (edge_key(u[size_t(kn)], u[size_t((kn + 1) % 3)]) != edge_key(a, b)) {
          bisect(n);  // make a-b the neighbour's longest edge first
          continue;
        }
      }
      const int m = midpoint(a, b);
      split(f, k, m);
      if (n >= 0) {
        const auto& u = faces_[size_t(n)];
        for (int kn = 0; kn < 3; ++kn)
          if (edge_key(u[size_t(kn)], u[size_t((kn + 1) % 3)]) == edge_key(a, b)) {
            split(n, kn, m);
            break;
          }
      }
      return;
    }
  }

  int midpoint(int a, int b) {
    const int m = int(vertices_.size());
    vertices_.push_back(0.5 * (vertices_[size_t(a)] + vertices_[size_t(b)]));
    mesh_.sides.push_back(mesh_.sides[size_t(a)] & mesh_.sides[size_t(b)]);
    z_.push_back(height_(vertices_.back()));
    return m;
  }

  // Splits triangle f along the edge starting at corner k at the new vertex m.
  void split(int f, int k, int m) {
    const std::array<int, 3> t = faces_[size_t(f)];
    const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)], c = t[size_t((k + 2) % 3)];
    detach(f);
    const auto split_edge = edges_.find(edge_key(a, b));
    if (split_edge != edges_.end() && split_edge->second[0] < 0 && split_edge->second[1] < 0)
      edges_.erase(split_edge);
    faces_[size_t(f)] = {a, m, c};
    faces_.push_back({m, b, c});
    stamp_[size_t(f)] = round_;
    stamp_.push_back(round_);
    // The two halves of a-b may already be known from the neighbour's split.
    attach(f);
    attach(int(faces_.size()) - 1);
  }

  PlanarMesh& mesh_;
  std::vector<double>& z_;
  const std::function<double(const Eigen::Vector2d&)>& height_;
  std::vector<Eigen::Vector2d> vertices_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<int> stamp_;
  std::unordered_map<uint64_t, std::array<int, 2>> edges_;
  int round_ = 0;
};

// Triangles the lift stretches (an edge longer than max_stretch times its planar length) or
// shears (a lifted angle below min_angle).
std::vector<int> marked_triangles(const Bisector& mesh, const std::vector<double>& z,
                                  const SubdivisionOptions& o) {
  const double cos_min = std::cos(o.min_angle * M_PI / 180.0);
  std::vector<int> marked;
  for (size_t f = 0; f < mesh.face_count(); ++f) {
    const auto& t = mesh.face(f);
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d v = mesh.vertex(t[size_t(k)]);
      p[k] = Eigen::Vector3d(v.x(), v.y(), z[size_t(t[size_t(k)])]);
    }
    bool mark = false;
    for (int k = 0; k < 3 && !mark; ++k) {
      const Eigen::Vector3d e = p[(k + 1) % 3] - p[k], g = p[(k + 2) % 3] - p[k];
      mark = e.norm() > o.max_stretch * e.head<2>().norm() ||
             e.normalized().dot(g.normalized()) > cos_min;
    }
    if (mark) marked.push_back(int(f));
  }
  return marked;
}

}  // namespace

void validate(const SubdivisionOptions& options) {
  require(std::isfinite(options.max_stretch) && options.max_stretch > 1, "validate",
          "max stretch must be > 1, got " + number_text(options.max_stretch));
  require(std::isfinite(options.min_angle) && options.min_angle >= 0 && options.min_angle < 60,
          "validate",
          "min angle must be in [0, 60) degrees, got " + number_text(options.min_angle));
  require_option(options.max_levels >= 0 && options.max_levels <= 8, "validate", "subdivide",
                 "must be in [0, 8] bisection rounds, got " + std::to_string(options.max_levels));
}

PlanarMesh subdivide(const PlanarMesh& mesh,
                     const std::function<double(const Eigen::Vector2d&)>& height,
                     const SubdivisionOptions& options) {
  validate(options);
  PlanarMesh out = mesh;
  std::vector<double> z(size_t(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) z[size_t(i)] = height(mesh.V.row(i).transpose());
  Bisector bisector(out, z, height);
  for (int level = 0; level < options.max_levels; ++level) {
    const std::vector<int> marked = marked_triangles(bisector, z, options);
    if (marked.empty()) break;
    bisector.refine(marked, level);
  }
  bisector.write_back();
  return out;
}

}  // namespace geolens
