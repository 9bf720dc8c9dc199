#pragma once

// A scene's bodies and ground as triangle meshes, for drawing and export: no sphere-trees, no
// world. Bodies share a mesh as build_world() shares their shapes.

#include <cstdint>
#include <memory>
#include <vector>

#include "sphys/tools/scene.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

// The body's mesh scaled to its size and moved so that its centre of mass is the origin: its
// body frame. Throws sphys::Error for a mesh that cannot be loaded.
[[nodiscard]] TriangleMesh body_frame_mesh(const Scene& scene, const BodySpec& body);

// A scene's bodies' meshes, each distinct shape once (scene_meshes).
struct SceneMeshes {
  std::vector<std::shared_ptr<const TriangleMesh>> shapes;  // body frame
  std::vector<std::uint32_t> body_shape;                    // index into shapes, per scene body
};

// Throws sphys::Error naming the scene and the body ("<scene>: /bodies/3: ...").
[[nodiscard]] SceneMeshes scene_meshes(const Scene& scene);

// The ground in the world frame: the octree ground's box, the plane as a square of side
// `plane_size` centred under the origin, nothing for no ground.
[[nodiscard]] TriangleMesh ground_mesh(const GroundSpec& ground, double plane_size);

}  // namespace sphys::tools
