#pragma once

// A recording as glTF 2.0 binary (.glb): the bodies' meshes, the ground, and the bodies' motion
// as one animation, so that Blender and web viewers play it.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>

#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// Which frames go in: first, first + every, ... up to last (inclusive).
struct GltfExportOptions {
  std::uint32_t first = 0;            // the first frame exported, from 0
  std::optional<std::uint32_t> last;  // unset: the recording's last frame
  std::uint32_t every = 1;            // the step between frames exported, >= 1. unit: frames
};

// What write_gltf wrote.
struct GltfExportSummary {
  std::uint32_t frames = 0;  // exported
  std::uint32_t bodies = 0;  // animated: every body of the recording
  std::uint32_t meshes = 0;  // distinct body meshes, the ground not counted
  std::uint64_t bytes = 0;   // of the file
};

// `scene` is the recording's (its metadata), for the meshes and the ground. `robot_meshes`: the
// meshes of the recording's bodies after the scene's, its robots' (tools::SceneRobots::shapes'),
// in the body frame; none for a recording of the scene's bodies alone. The file is written whole
// or not at all. Throws sphys::Error for a frame range outside the recording, every = 0, a
// recording whose body count is not the scene's and the robot meshes', a mesh that cannot be
// loaded, and a file that cannot be written.
GltfExportSummary write_gltf(
    const std::filesystem::path& path, const Recording& recording, const Scene& scene,
    const GltfExportOptions& options = {},
    std::span<const std::shared_ptr<const TriangleMesh>> robot_meshes = {});

}  // namespace sphys::tools
