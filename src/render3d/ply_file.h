#pragma once
// Stanford PLY meshes, read by a small reader of the project's own (the format is a text
// header of elements and properties followed by ASCII or binary rows; no Debian library is
// smaller than this reader).

#include <string>

#include "render3d/triangle_mesh.h"

namespace geolens {

/// Reads the "vertex" element (properties x, y, z, and nx, ny, nz when all three are there) and
/// the "face" element (a list property named vertex_indices or vertex_index; polygons fanned
/// into triangles from their first corner) of a PLY file in format ascii, binary_little_endian
/// or binary_big_endian 1.0. Other elements and properties are skipped, any of the scalar types
/// char/int8 ... double/float64. Throws InvalidInput naming "load_ply" and the file, with the
/// header line, or the element and row, at fault: a malformed header, a missing x/y/z or face
/// list, an x, y, z, nx, ny or nz declared a list, a row with too few values, a face with fewer
/// than 3 corners or naming a missing vertex, data that ends before the header's counts, and a mesh
/// with no face, more than `max_vertices` vertices (>= 1; refused from the header) and a file over
/// mesh_bytes_limit(max_vertices).
TriangleMesh load_ply(const std::string& path, size_t max_vertices = kMaxMeshVertices);

}  // namespace geolens
