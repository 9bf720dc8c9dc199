#pragma once

// A scene's robots (Scene::robots) added to the world build_world made of it: each loaded from its
// files, put where the scene says and, with targets, held there by position control; with their
// bodies' shapes and joints, which recordings and the viewer keep after the scene's own.

#include <cstdint>
#include <vector>

#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"
#include "sphys/world.h"

namespace sphys::tools {

// The scene's robots in its world, with what the tools need to record and draw them.
struct SceneRobots {
  std::vector<RobotId> robots;  // in the scene's order
  // Every robot's bodies (World::robot_bodies), robot after robot.
  std::vector<BodyId> bodies;
  // One per body: the sphere-tree the world made of its links' spheres, and the meshes of the
  // links it carries (their collision geometry, else their visual one) in the body frame, named
  // "<robot>: <link>". Their volume and max_vertex_distance are not measured (0).
  std::vector<BodyShape> shapes;
  // Every robot's joints (World::robot_joints) as a recording keeps them, their bodies indices
  // into `bodies`.
  std::vector<RecordedJoint> joints;
};

// Adds the scene's robots to `world`, in order. Throws sphys::Error naming the robot
// ("<scene>: /robots/<k>: ...") for a file that does not load, or a configuration or targets
// that are not one value per joint within its limits.
SceneRobots add_scene_robots(const Scene& scene, World& world);

// Appends the robot's bodies (World::robot_bodies) to `bodies` and its joints, as a recording
// keeps them, to `joints`, their bodies indices into `bodies`: what a recording of the world keeps
// of a robot after the bodies already listed, as add_scene_robots keeps the scene's robots.
void append_recorded_robot(const World& world, RobotId robot, std::vector<BodyId>& bodies,
                           std::vector<RecordedJoint>& joints);

// Whether a recording of `body_count` bodies keeps the robots' bodies after the scene's, as
// `sphys simulate` records them; false for one that keeps the scene's alone, as recordings made
// before robots were recorded do. Throws sphys::Error for any other count.
[[nodiscard]] bool recording_keeps_robots(const Scene& scene, const SceneRobots& robots,
                                          std::uint32_t body_count);

// The joints a recording of the scene and its robots keeps: the scene's (recorded_joints), then
// the robots', their bodies counted after the scene's.
[[nodiscard]] std::vector<RecordedJoint> recorded_joints(const Scene& scene,
                                                         const SceneRobots& robots);

}  // namespace sphys::tools
