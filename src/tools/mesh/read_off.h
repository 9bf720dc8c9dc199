#pragma once

#include <filesystem>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Reads an ASCII OFF file (OFF, COFF, NOFF, CNOFF headers; '#' comments; extra per-vertex and
// per-face fields such as colours are ignored; polygons are fan-triangulated). Our own reader
// because assimp's clamps out-of-range face indices silently. Errors name the line.
[[nodiscard]] TriangleMesh read_off(const std::filesystem::path& path);

}  // namespace sphys::tools
