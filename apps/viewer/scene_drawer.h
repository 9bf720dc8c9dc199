#pragma once

// Draws a frame of a scene: the ground and the bodies' meshes in the sun's shadows, and the
// overlays (sphere-tree level, contacts and normals, broad-phase boxes, joints, sleeping tint).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "body_view.h"
#include "camera.h"
#include "lines.h"
#include "renderer.h"
#include "sphys/contact.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"

namespace sphys::viewer {

struct Overlays {
  int sphere_level = 0;  // tree level drawn see-through, 1 the root; 0: none
  bool contacts = false;
  bool boxes = false;
  bool joints = true;  // each joint's anchors and the arms from its bodies' centres
  bool sleeping_tint = true;
  bool shadows = true;  // the sun's, cast by the bodies
};

struct FrameContents {
  std::span<const BodyView> bodies;
  std::span<const Contact> contacts;  // empty for a replay
  std::span<const Aabb> boxes;        // empty for a replay
  // Their bodies are indices into `bodies`.
  std::span<const tools::RecordedJoint> joints;
};

class SceneDrawer {
 public:
  // Uploads the shapes' meshes and the ground's. The scene and the shapes must outlive it.
  SceneDrawer(Renderer& renderer, const tools::Scene& scene,
              const std::vector<tools::BodyShape>& shapes);

  void draw(Renderer& renderer, LineRenderer& lines, const OrbitCamera& camera, float aspect,
            const FrameContents& frame, const Overlays& overlays);

 private:
  void draw_spheres(Renderer& renderer, std::span<const BodyView> bodies, int level) const;
  void draw_contacts(LineRenderer& lines, std::span<const Contact> contacts);
  void draw_boxes(LineRenderer& lines, std::span<const Aabb> boxes);
  void draw_joints(LineRenderer& lines, std::span<const BodyView> bodies,
                   std::span<const tools::RecordedJoint> joints);

  const tools::Scene* scene_;
  const std::vector<tools::BodyShape>* shapes_;
  std::vector<std::uint32_t> shape_meshes_;
  std::optional<std::uint32_t> ground_;
  std::uint32_t sphere_ = 0;
  std::vector<Eigen::Vector3f> points_;      // line end points, reused
  std::vector<Eigen::Vector3f> gap_points_;  // those of the joints drawn in the gap's colour
};

// Looks at the middle of the bodies' starting positions and the robots (their roots and a metre
// above), low enough to see the ground, from far enough to see the ground's box (or their spread)
// whole.
[[nodiscard]] OrbitCamera frame_scene(const tools::Scene& scene);

// The plane drawn for an infinite ground plane. unit: m
inline constexpr double kPlaneSize = 120.0;

}  // namespace sphys::viewer
