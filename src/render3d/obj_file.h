#pragma once
// Wavefront OBJ meshes, read with tinyobjloader (Debian's libtinyobjloader-dev).

#include <string>

#include "render3d/triangle_mesh.h"

namespace geolens {

/// Reads the vertices (v) and faces (f) of every object of an OBJ file into one mesh, polygons
/// triangulated; texture coordinates and materials are ignored (a missing .mtl is not an
/// error). Vertex normals (vn) are kept when every corner of a vertex names the same normal,
/// otherwise dropped (then computed from the faces). Throws InvalidInput naming "load_obj" and
/// the file, with tinyobjloader's account (which names the line) for a malformed file, for a
/// face naming a missing vertex, for a file with no face, for more than `max_vertices` vertices
/// (>= 1; counted before they are parsed) and for a file over mesh_bytes_limit(max_vertices).
TriangleMesh load_obj(const std::string& path, size_t max_vertices = kMaxMeshVertices);

}  // namespace geolens
