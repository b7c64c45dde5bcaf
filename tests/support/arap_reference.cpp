#include "support/arap_reference.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace geolens::testing {
namespace {

/// What the energy needs of one triangle.
struct Triangle {
  std::array<int, 3> v;       // vertex indices
  double area;                // area in V3, L^2
  Eigen::Matrix2d S_inverse;  // inverse of the standard triangle's edge matrix [s2 - s1, s3 - s1]
};

/// Validates the inputs and builds every triangle's standard triangle.
std::vector<Triangle> prepare(const char* function, const Eigen::MatrixX3d& V3,
                              const Eigen::MatrixX3i& F, const Eigen::MatrixX2d& X) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(std::string(function) + ": " + what);
  };
  if (X.rows() != V3.rows()) {
    fail("X has " + std::to_string(X.rows()) + " rows but V3 has " + std::to_string(V3.rows()));
  }
  if (!V3.allFinite()) fail("V3 has a non-finite coordinate");
  if (!X.allFinite()) fail("X has a non-finite coordinate");

  std::vector<Triangle> triangles;
  triangles.reserve(F.rows());
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    Triangle triangle{};
    for (int k = 0; k < 3; ++k) {
      triangle.v[k] = F(t, k);
      if (F(t, k) < 0 || F(t, k) >= V3.rows()) {
        fail("F(" + std::to_string(t) + ", " + std::to_string(k) +
             ") = " + std::to_string(F(t, k)) + " is not a vertex index in [0, " +
             std::to_string(V3.rows()) + ")");
      }
    }
    const Eigen::Vector3d p1 = V3.row(triangle.v[0]).transpose();
    const Eigen::Vector3d e12 = V3.row(triangle.v[1]).transpose() - p1;
    const Eigen::Vector3d e13 = V3.row(triangle.v[2]).transpose() - p1;
    const double cross = e12.cross(e13).norm();  // twice the area
    const double longest =
        std::max({e12.squaredNorm(), e13.squaredNorm(), (e13 - e12).squaredNorm()});
    if (!(cross > 1e-12 * longest)) {
      fail("triangle " + std::to_string(t) + " is degenerate in V3 (area " +
           std::to_string(0.5 * cross) + ")");
    }
    // Standard triangle: s1 = (0, 0), s2 = (|e12|, 0), s3 = (e13 . e12 / |e12|, 2 area / |e12|),
    // so |s2 - s1| = |e12|, |s3 - s1| = |e13| and s3 is above the x axis.
    const double base = e12.norm();
    Eigen::Matrix2d S;
    S << base, e12.dot(e13) / base, 0, cross / base;
    triangle.area = 0.5 * cross;
    triangle.S_inverse = S.inverse();
    triangles.push_back(triangle);
  }
  return triangles;
}

/// Jacobian of the affine map from the standard triangle to its image in X: J = D S^-1 with
/// D = [x2 - x1, x3 - x1].
Eigen::Matrix2d jacobian(const Triangle& triangle, const Eigen::MatrixX2d& X) {
  Eigen::Matrix2d D;
  D.col(0) = (X.row(triangle.v[1]) - X.row(triangle.v[0])).transpose();
  D.col(1) = (X.row(triangle.v[2]) - X.row(triangle.v[0])).transpose();
  return D * triangle.S_inverse;
}

/// The rotation closest to J in the Frobenius norm, in closed form: R(theta) minimizes
/// ||J - R||^2 = ||J||^2 + 2 - 2 tr(R^T J) with tr(R^T J) = cos(theta) (J00 + J11) +
/// sin(theta) (J10 - J01), which is largest at theta = atan2(J10 - J01, J00 + J11).
Eigen::Matrix2d closest_rotation(const Eigen::Matrix2d& J) {
  const double theta = std::atan2(J(1, 0) - J(0, 1), J(0, 0) + J(1, 1));
  Eigen::Matrix2d R;
  R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return R;
}

double energy(const std::vector<Triangle>& triangles, const Eigen::MatrixX2d& X) {
  double sum = 0;
  for (const Triangle& triangle : triangles) {
    const Eigen::Matrix2d J = jacobian(triangle, X);
    sum += triangle.area * (J - closest_rotation(J)).squaredNorm();
  }
  return sum;
}

Eigen::MatrixX2d gradient(const std::vector<Triangle>& triangles, const Eigen::MatrixX2d& X) {
  Eigen::MatrixX2d G = Eigen::MatrixX2d::Zero(X.rows(), 2);
  for (const Triangle& triangle : triangles) {
    const Eigen::Matrix2d J = jacobian(triangle, X);
    // dE/dD = dE/dJ S^-T; column 0 of D is x2 - x1, column 1 is x3 - x1.
    const Eigen::Matrix2d dD =
        2 * triangle.area * (J - closest_rotation(J)) * triangle.S_inverse.transpose();
    G.row(triangle.v[1]) += dD.col(0).transpose();
    G.row(triangle.v[2]) += dD.col(1).transpose();
    G.row(triangle.v[0]) -= (dD.col(0) + dD.col(1)).transpose();
  }
  return G;
}

}  // namespace

double arap_energy(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                   const Eigen::MatrixX2d& X) {
  return energy(prepare("arap_energy", V3, F, X), X);
}

Eigen::MatrixX2d arap_gradient(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                               const Eigen::MatrixX2d& X) {
  return gradient(prepare("arap_gradient", V3, F, X), X);
}

Eigen::MatrixX2d arap_descend(const Eigen::MatrixX3d& V3, const Eigen::MatrixX3i& F,
                              const Eigen::MatrixX2d& X0, int iterations) {
  const std::vector<Triangle> triangles = prepare("arap_descend", V3, F, X0);
  if (iterations < 0) {
    throw std::invalid_argument("arap_descend: iterations = " + std::to_string(iterations) +
                                " is negative");
  }
  constexpr double kArmijo = 1e-4;  // fraction of the linear decrease a step must achieve
  Eigen::MatrixX2d X = X0;
  double E = energy(triangles, X);
  double step = 1;  // dimensionless: E's Hessian in X is dimensionless, of order 1 per vertex
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::MatrixX2d g = gradient(triangles, X);
    g.rowwise() -= g.colwise().mean();  // exactly 0 already; drops round-off that would drift
    const double slope = g.squaredNorm();
    while (true) {
      const Eigen::MatrixX2d trial = X - step * g;
      // A step too small to move any vertex cannot lower E: X is as low as descent gets.
      if (trial == X) return X;
      const double trial_energy = energy(triangles, trial);
      if (trial_energy <= E - kArmijo * step * slope) {
        X = trial;
        E = trial_energy;
        break;
      }
      step /= 2;
    }
    step *= 2;  // let the next line search try a longer step first
  }
  return X;
}

void read_obj(const std::string& path, Eigen::MatrixX3d& V, Eigen::MatrixX3i& F) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("read_obj: cannot open '" + path + "'");

  int line_number = 0;
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error("read_obj: " + path + ":" + std::to_string(line_number) + ": " + what);
  };
  const std::set<std::string, std::less<>> ignored{"vt", "vn", "o", "g", "s", "usemtl", "mtllib"};
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_lines;  // line of each face, for error messages
  for (std::string line; std::getline(file, line);) {
    ++line_number;
    std::istringstream tokens(line.substr(0, line.find('#')));
    std::string keyword;
    if (!(tokens >> keyword)) continue;  // blank line or comment
    std::vector<std::string> arguments;
    for (std::string argument; tokens >> argument;) arguments.push_back(argument);

    if (keyword == "v") {
      if (arguments.size() != 3) fail("a vertex needs exactly 3 coordinates: '" + line + "'");
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        const std::string& a = arguments[k];
        const auto [end, error] = std::from_chars(a.data(), a.data() + a.size(), p[k]);
        if (error != std::errc() || end != a.data() + a.size() || !std::isfinite(p[k])) {
          fail("'" + a + "' is not a finite number");
        }
      }
      vertices.push_back(p);
    } else if (keyword == "f") {
      if (arguments.size() != 3) fail("a face needs exactly 3 vertices: '" + line + "'");
      std::array<int, 3> face{};
      for (int k = 0; k < 3; ++k) {
        const std::string_view a = std::string_view(arguments[k]).substr(0, arguments[k].find('/'));
        int index = 0;
        const auto [end, error] = std::from_chars(a.data(), a.data() + a.size(), index);
        if (error != std::errc() || end != a.data() + a.size() || index < 1) {
          fail("'" + arguments[k] + "' is not a 1-based vertex reference");
        }
        face[k] = index - 1;
      }
      faces.push_back(face);
      face_lines.push_back(line_number);
    } else if (!ignored.contains(keyword)) {
      fail("unsupported statement '" + keyword + "'");
    }
  }
  if (file.bad()) throw std::runtime_error("read_obj: error reading '" + path + "'");

  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (const int index : faces[f]) {
      if (index >= static_cast<int>(vertices.size())) {
        line_number = face_lines[f];
        fail("vertex " + std::to_string(index + 1) + " does not exist, the file has " +
             std::to_string(vertices.size()) + " vertices");
      }
    }
  }
  V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) V.row(i) = vertices[i].transpose();
  F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) F.row(f) << faces[f][0], faces[f][1], faces[f][2];
}

}  // namespace geolens::testing
