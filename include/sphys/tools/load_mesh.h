#pragma once

#include <filesystem>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Reads a triangle mesh from OBJ, PLY, STL or OFF (anything assimp reads), applies the file's node
// transforms, triangulates polygons, ignores points and lines, and welds vertices that share a
// position exactly. Throws sphys::Error naming the file and the problem when the file is missing,
// empty, unreadable, holds a non-finite coordinate or an out-of-range face index, or has no
// triangles.
[[nodiscard]] TriangleMesh load_mesh(const std::filesystem::path& path);

// Merges vertices with identical coordinates and renumbers triangles accordingly; drops vertices
// no triangle uses. Keeps degenerate triangles (check_mesh reports them).
[[nodiscard]] TriangleMesh weld_vertices(const TriangleMesh& mesh);

}  // namespace sphys::tools
