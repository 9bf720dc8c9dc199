#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string_view>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// The default model: the Stanford bunny as Debian's glmark2-data ships it. The environment
// variable SPHYS_BUNNY overrides the path.
inline constexpr std::string_view kBunnyName = "bunny";
inline constexpr std::size_t kBunnyDefaultTriangles = 2000;  // what "bunny" is decimated to
// SPHYS_BUNNY when set and not empty, else glmark2-data's /usr/share/glmark2/models/bunny.obj.
[[nodiscard]] std::filesystem::path bunny_path();

// Resolves what a user typed where a mesh is accepted: "bunny" is the default model decimated to
// `triangles` (kBunnyDefaultTriangles if unset; 0 keeps every triangle); anything else is a mesh
// file, decimated only when `triangles` is given and non-zero.
[[nodiscard]] TriangleMesh load_model(std::string_view spec,
                                      std::optional<std::size_t> triangles = std::nullopt);

}  // namespace sphys::tools
