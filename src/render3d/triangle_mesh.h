#pragma once
// A triangle mesh in 3D (what a mesh file holds), its normals and its bounding sphere.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

namespace geolens {

/// Triangles in model space, as read from an OBJ or PLY file (polygons fanned into triangles).
struct TriangleMesh {
  Eigen::MatrixXd V;  ///< #V x 3 vertex positions, model units
  Eigen::MatrixXi F;  ///< #F x 3 vertex indices into V, counter-clockwise seen from outside
  Eigen::MatrixXd N;  ///< #V x 3 unit vertex normals from the file, or 0 x 3 (none given)
};

/// The most vertices the mesh readers (load_obj, load_ply) read by default: 2^22 (4 194 304, about
/// eight million triangles); they take another limit (--max-vertices).
inline constexpr size_t kMaxMeshVertices = size_t(1) << 22;

/// The most bytes of a mesh file read with a limit of `max_vertices`: 128 a vertex (a vertex and
/// its two triangles as text), at least 512 MiB.
inline size_t mesh_bytes_limit(size_t max_vertices) {
  return std::max(size_t(512) << 20, std::min(max_vertices, size_t(1) << 36) * 128);
}

/// What a reader says of a mesh of `vertices` over `max_vertices`, naming the limit.
std::string vertex_limit_message(uint64_t vertices, size_t max_vertices);

/// #F x 3 unit face normals by the right-hand rule (counter-clockwise = towards the viewer); a
/// zero row for a degenerate (zero-area) face.
Eigen::MatrixXd face_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// #V x 3 unit vertex normals: the area-weighted mean of the normals of the faces around each
/// vertex (the sum of the faces' cross products, normalized); a zero row for a vertex in no
/// face of positive area.
Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

/// Throws InvalidInput naming `function` and `file` for a mesh with no triangle, a non-finite
/// vertex, a face index outside [0, #V) or vertex normals of the wrong shape.
void check_triangle_mesh(const TriangleMesh& mesh, const char* function, const std::string& file);

/// The centre (the middle of the bounding box) and the radius of a sphere around the vertices
/// used by F, model units; the radius is > 0 (a tiny positive value for a single point).
void bounding_sphere(const TriangleMesh& mesh, Eigen::Vector3d& centre, double& radius);

}  // namespace geolens
