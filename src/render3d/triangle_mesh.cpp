#include "render3d/triangle_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/limits.h"
#include "geolens/core/errors.h"

namespace geolens {

namespace {

Eigen::Vector3d cross_of(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(),
                        c = V.row(F(f, 2)).transpose();
  return (b - a).cross(c - a);
}

}  // namespace

Eigen::MatrixXd face_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d n = cross_of(V, F, f);
    const double length = n.norm();
    if (length > 0) N.row(f) = n.transpose() / length;
  }
  return N;
}

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d n = cross_of(V, F, f).transpose();
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double length = N.row(v).norm();
    if (length > 0) N.row(v) /= length;
  }
  return N;
}

void check_triangle_mesh(const TriangleMesh& mesh, const char* function, const std::string& file) {
  const std::string where = "'" + file + "': ";
  require(mesh.F.rows() > 0, function, where + "the mesh has no triangle");
  require(mesh.V.cols() == 3 && mesh.F.cols() == 3, function,
          where + "vertices and faces must have 3 columns");
  require(mesh.V.allFinite(), function, where + "a vertex coordinate is not finite");
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      require(mesh.F(f, k) >= 0 && mesh.F(f, k) < mesh.V.rows(), function,
              where + "face " + std::to_string(f) + " names vertex " +
                  std::to_string(mesh.F(f, k)) + ", outside [0, " + std::to_string(mesh.V.rows()) +
                  ")");
  require(mesh.N.rows() == 0 || (mesh.N.rows() == mesh.V.rows() && mesh.N.cols() == 3), function,
          where + "there must be one normal per vertex or none");
}

void bounding_sphere(const TriangleMesh& mesh, Eigen::Vector3d& centre, double& radius) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY),
                  high = Eigen::Vector3d::Constant(-INFINITY);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(f, k)).transpose();
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  centre = (low + high) / 2;
  radius = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      radius = std::max(radius, (mesh.V.row(mesh.F(f, k)).transpose() - centre).norm());
  radius = std::max(radius, 1e-9 * std::max(1.0, centre.norm()));
}

std::string vertex_limit_message(uint64_t vertices, size_t max_vertices) {
  return std::to_string(vertices) + " vertices, " + over_limit(max_vertices, "max_vertices");
}

}  // namespace geolens
