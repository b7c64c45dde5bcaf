// Tests of the independent ARAP reference in support/arap_reference.h: the energy's defining
// properties, its gradient, the descent, the cotan edge form, and OBJ reading.

#include "support/arap_reference.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace {

using geolens::testing::arap_descend;
using geolens::testing::arap_energy;
using geolens::testing::arap_gradient;
using geolens::testing::read_obj;

struct Mesh {
  Eigen::MatrixX3d V;  // #V x 3
  Eigen::MatrixX3i F;  // #F x 3
};

/// An n x n vertex grid with unit spacing in the plane z = 0, cells split along alternating
/// diagonals, triangles counter-clockwise in (x, y).
Mesh grid(int n) {
  Mesh m;
  m.V.resize(n * n, 3);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) m.V.row(y * n + x) << x, y, 0;
  }
  m.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int y = 0; y + 1 < n; ++y) {
    for (int x = 0; x + 1 < n; ++x) {
      const int a = y * n + x, b = a + 1, c = a + n, d = c + 1;
      if ((x + y) % 2 == 0) {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << a, d, c;
      } else {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      }
    }
  }
  return m;
}

/// The grid lifted onto a smooth, non-developable bump.
Mesh bumpy_grid(int n) {
  Mesh m = grid(n);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    m.V(i, 2) = 0.8 * std::sin(0.9 * m.V(i, 0)) * std::cos(0.7 * m.V(i, 1));
  }
  return m;
}

/// X moved by a fixed, irregular offset of at most `amplitude` per coordinate.
Eigen::MatrixX2d perturbed(Eigen::MatrixX2d X, double amplitude) {
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    X(i, 0) += amplitude * std::sin(12.9898 * i + 1.0);
    X(i, 1) += amplitude * std::cos(78.233 * i + 2.0);
  }
  return X;
}

double total_area(const Mesh& m) {
  double area = 0;
  for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
    const Eigen::Vector3d a = m.V.row(m.F(t, 0)), b = m.V.row(m.F(t, 1)), c = m.V.row(m.F(t, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

Eigen::MatrixX2d flat(const Mesh& m) { return m.V.leftCols<2>(); }

TEST(ArapReference, IsometricFlatteningOfAFlatMeshHasZeroEnergy) {
  const Mesh m = grid(6);
  EXPECT_NEAR(arap_energy(m.V, m.F, flat(m)), 0, 1e-24);
}

TEST(ArapReference, RigidMotionsHaveZeroEnergy) {
  const Mesh m = grid(6);
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  const Eigen::MatrixX2d moved =
      (flat(m) * rotation.transpose()).rowwise() + Eigen::RowVector2d(3.5, -2.25);
  EXPECT_NEAR(arap_energy(m.V, m.F, moved), 0, 1e-20);

  // The 3D mesh moved rigidly in space still flattens isometrically onto the original grid.
  const Eigen::Matrix3d spin =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d V3 = (m.V * spin.transpose()).rowwise() + Eigen::RowVector3d(4, -1, 7);
  EXPECT_NEAR(arap_energy(V3, m.F, flat(m)), 0, 1e-20);
}

TEST(ArapReference, StretchAndMirrorCostTheExpectedEnergy) {
  const Mesh m = grid(6);
  // J = diag(1.3, 1) Q with Q a rotation: the closest rotation is Q, ||J - Q||^2 = 0.3^2.
  Eigen::MatrixX2d stretched = flat(m);
  stretched.col(0) *= 1.3;
  EXPECT_GT(arap_energy(m.V, m.F, stretched), 0);
  EXPECT_NEAR(arap_energy(m.V, m.F, stretched), 0.09 * total_area(m), 1e-12);

  // A mirrored triangle is orthogonal with det -1: its distance to the rotations is
  // ||J - R||^2 = 4 for every rotation R, so the mirror costs 4 per unit area.
  Eigen::MatrixX2d mirrored = flat(m);
  mirrored.col(0) *= -1;
  EXPECT_NEAR(arap_energy(m.V, m.F, mirrored), 4 * total_area(m), 1e-12);
}

TEST(ArapReference, GradientMatchesCentralDifferences) {
  const Mesh m = bumpy_grid(5);
  const Eigen::MatrixX2d X = perturbed(1.1 * flat(m), 0.2);
  const Eigen::MatrixX2d G = arap_gradient(m.V, m.F, X);
  ASSERT_EQ(G.rows(), X.rows());
  const double h = 1e-6;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (int c = 0; c < 2; ++c) {
      Eigen::MatrixX2d plus = X, minus = X;
      plus(i, c) += h;
      minus(i, c) -= h;
      const double numeric = (arap_energy(m.V, m.F, plus) - arap_energy(m.V, m.F, minus)) / (2 * h);
      EXPECT_NEAR(G(i, c), numeric, 1e-7 * std::max(1.0, std::abs(numeric)))
          << "vertex " << i << ", coordinate " << c;
    }
  }
  // E is invariant to translation, so the gradient has no translation component.
  EXPECT_NEAR(G.col(0).sum(), 0, 1e-12);
  EXPECT_NEAR(G.col(1).sum(), 0, 1e-12);
}

TEST(ArapReference, DescentOnlyLowersTheEnergy) {
  const Mesh m = bumpy_grid(5);
  const Eigen::MatrixX2d X0 = perturbed(flat(m), 0.3);
  EXPECT_EQ(arap_descend(m.V, m.F, X0, 0), X0);
  double previous = arap_energy(m.V, m.F, X0);
  for (const int iterations : {1, 2, 4, 8, 16, 32}) {
    const double E = arap_energy(m.V, m.F, arap_descend(m.V, m.F, X0, iterations));
    EXPECT_LT(E, previous) << iterations << " iterations";
    previous = E;
  }
}

TEST(ArapReference, DescentFromAPerturbedFlatMeshReachesZeroEnergy) {
  const Mesh m = grid(6);
  const Eigen::MatrixX2d X0 = perturbed(flat(m), 0.1);
  const double E0 = arap_energy(m.V, m.F, X0);
  ASSERT_GT(E0, 1e-3);
  const Eigen::MatrixX2d X = arap_descend(m.V, m.F, X0, 2000);
  EXPECT_LT(arap_energy(m.V, m.F, X), 1e-12 * E0);
  // Zero energy means a rigid copy of the grid: every edge has its original length.
  for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int i = m.F(t, k), j = m.F(t, (k + 1) % 3);
      EXPECT_NEAR((X.row(i) - X.row(j)).norm(), (m.V.row(i) - m.V.row(j)).norm(), 1e-5);
    }
  }
  // No vertex is pinned and the descent does not translate the mesh.
  EXPECT_NEAR((X.colwise().mean() - X0.colwise().mean()).norm(), 0, 1e-12);
}

TEST(ArapReference, DescentOnACurvedMeshReachesAStationaryPoint) {
  const Mesh m = bumpy_grid(5);
  const Eigen::MatrixX2d X0 = perturbed(flat(m), 0.3);
  const Eigen::MatrixX2d X = arap_descend(m.V, m.F, X0, 3000);
  EXPECT_LT(arap_energy(m.V, m.F, X), arap_energy(m.V, m.F, X0));
  EXPECT_LT(arap_gradient(m.V, m.F, X).norm(), 1e-6 * arap_gradient(m.V, m.F, X0).norm());
}

/// sum_t sum_{edges ij of t} cot(theta_ij) ||x_i - x_j - R_t (s_i - s_j)||^2 / 2, with the
/// standard triangles built from angles and R_t from an SVD: nothing shared with the reference.
double cotan_edge_energy(const Mesh& m, const Eigen::MatrixX2d& X) {
  double sum = 0;
  for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
    std::array<Eigen::Vector3d, 3> p;
    std::array<Eigen::Vector2d, 3> x, s;
    for (int k = 0; k < 3; ++k) {
      p[k] = m.V.row(m.F(t, k)).transpose();
      x[k] = X.row(m.F(t, k)).transpose();
    }
    const double angle1 =
        std::atan2((p[1] - p[0]).cross(p[2] - p[0]).norm(), (p[1] - p[0]).dot(p[2] - p[0]));
    s[0] = {0, 0};
    s[1] = {(p[1] - p[0]).norm(), 0};
    s[2] = (p[2] - p[0]).norm() * Eigen::Vector2d(std::cos(angle1), std::sin(angle1));

    Eigen::Matrix2d S, D;
    S << s[1] - s[0], s[2] - s[0];
    D << x[1] - x[0], x[2] - x[0];
    const Eigen::JacobiSVD<Eigen::Matrix2d> svd(D * S.inverse(),
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix2d U = svd.matrixU();
    if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(1) *= -1;
    const Eigen::Matrix2d R = U * svd.matrixV().transpose();

    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;  // the edge opposite vertex k
      const Eigen::Vector3d a = p[i] - p[k], b = p[j] - p[k];
      const double cot = a.dot(b) / a.cross(b).norm();
      sum += 0.5 * cot * (x[i] - x[j] - R * (s[i] - s[j])).squaredNorm();
    }
  }
  return sum;
}

TEST(ArapReference, EnergyEqualsTheCotanEdgeForm) {
  // Exactly, factor 1: for an affine map with Jacobian M on a triangle of area A,
  // A ||M||_F^2 = sum_k cot(theta_k) ||M e_k||^2 / 2, applied to M = J - R.
  const Mesh m = bumpy_grid(5);
  Eigen::MatrixX2d mirrored = flat(m);
  mirrored.col(0) *= -1;
  for (const Eigen::MatrixX2d& X :
       {perturbed(flat(m), 0.1), perturbed(0.7 * flat(m), 0.45), perturbed(mirrored, 0.2)}) {
    const double E = arap_energy(m.V, m.F, X);
    ASSERT_GT(E, 0);
    EXPECT_NEAR(E, cotan_edge_energy(m, X), 1e-12 * E);
  }
}

TEST(ArapReference, RejectsInvalidInput) {
  const Mesh m = grid(3);
  EXPECT_THROW(arap_energy(m.V, m.F, flat(m).topRows(5)), std::invalid_argument);
  Eigen::MatrixX3i F = m.F;
  F(2, 1) = 9;
  EXPECT_THROW(arap_energy(m.V, F, flat(m)), std::invalid_argument);
  F(2, 1) = F(2, 0);  // degenerate triangle
  EXPECT_THROW(arap_gradient(m.V, F, flat(m)), std::invalid_argument);
  EXPECT_THROW(arap_descend(m.V, m.F, flat(m), -1), std::invalid_argument);
}

/// Writes `text` to a file in GoogleTest's temporary directory and returns its path.
std::string write_temporary(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "arap_reference_test_" + name + ".obj";
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(ArapReference, ReadsAnObjFile) {
  const std::string path = write_temporary("square",
                                           "# a unit square in two triangles, and two more\n"
                                           "mtllib square.mtl\n"
                                           "o square\n"
                                           "v 0 0 0\n"
                                           "v 1 0 0.5\r\n"
                                           "v 1 1 -2.5e-1  # trailing comment\n"
                                           "v 0 1 0\n"
                                           "vt 0 0\n"
                                           "vn 0 0 1\n"
                                           "\n"
                                           "f 1 2 3\n"
                                           "f 1/1 3/1 4/1\n"
                                           "f 4//1 3//1 2//1\n"
                                           "f 2/1/1 4/1/1 1/1/1\n");
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  read_obj(path, V, F);
  Eigen::MatrixX3d expected_V(4, 3);
  expected_V << 0, 0, 0, 1, 0, 0.5, 1, 1, -0.25, 0, 1, 0;
  Eigen::MatrixX3i expected_F(4, 3);
  expected_F << 0, 1, 2, 0, 2, 3, 3, 2, 1, 1, 3, 0;
  EXPECT_EQ(V, expected_V);
  EXPECT_EQ(F, expected_F);
}

TEST(ArapReference, RejectsMalformedObjFiles) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::array<std::pair<const char*, std::string>, 8> cases{{
      {"two_coordinates", "v 0 0\n"},
      {"not_a_number", "v 0 0 x\n"},
      {"not_finite", "v 0 0 nan\n"},
      {"quad", vertices + "v 1 1 0\nf 1 2 4 3\n"},
      {"zero_index", vertices + "f 0 1 2\n"},
      {"index_out_of_range", vertices + "f 1 2 4\n"},
      {"bad_reference", vertices + "f 1 b/2 3\n"},
      {"polyline", vertices + "l 1 2\n"},
  }};
  for (const auto& [name, text] : cases) {
    Eigen::MatrixX3d V;
    Eigen::MatrixX3i F;
    EXPECT_THROW(read_obj(write_temporary(name, text), V, F), std::runtime_error) << name;
  }
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  EXPECT_THROW(read_obj(::testing::TempDir() + "arap_reference_test_missing.obj", V, F),
               std::runtime_error);
}

}  // namespace
