#pragma once

#include <filesystem>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Reads a PLY file, ASCII or binary (either byte order): the vertex element's x, y, z (any
// scalar type) and the face element's index list (vertex_indices or vertex_index), polygons
// fan-triangulated; every other property and element is skipped by its declared layout. Our own
// reader because assimp's aborts or loops for ever on some malformed headers. The header's
// counts are checked against the file's size before anything is allocated, so the work is linear
// in the file's size whatever the header claims. Errors name the file and the line (ASCII) or
// the element and record (binary).
[[nodiscard]] TriangleMesh read_ply(const std::filesystem::path& path);

}  // namespace sphys::tools
