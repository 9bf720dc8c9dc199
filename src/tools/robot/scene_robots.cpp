#include "sphys/tools/scene_robots.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sphys/error.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/tools/scene_file.h"

namespace sphys::tools {
namespace {

// The robot body (an index into World::robot_bodies: the root's first, then each joint's link's)
// that carries the link: its own when a joint moves it, else that of the link it is fixed to.
std::size_t carrying_body(const RobotModel& model, std::size_t link) {
  while (link != 0 && model.links[link].joint < 0) {
    link = static_cast<std::size_t>(model.links[link].parent);
  }
  return link == 0 ? 0 : static_cast<std::size_t>(model.links[link].joint) + 1;
}

// One shape per body of the robot: the world's tree of it, and the meshes of its links moved into
// its frame from where the world has them now.
void add_shapes(const Robot& robot, const World& world, RobotId id, std::vector<BodyShape>& out) {
  const RobotModel& model = world.robot_model(id);
  const std::span<const BodyId> bodies = world.robot_bodies(id);
  const std::vector<Eigen::Isometry3d> link_poses = world.robot_link_poses_in_world(id);
  const std::size_t first = out.size();
  for (const BodyId body : bodies) {
    BodyShape shape;
    shape.tree = world.shared_tree(body);
    shape.tree_source = "robot link spheres";
    out.push_back(std::move(shape));
  }
  std::vector<TriangleMesh> meshes(bodies.size());
  for (std::size_t link = 0; link < model.links.size(); ++link) {
    const std::size_t b = carrying_body(model, link);
    BodyShape& shape = out[first + b];
    if (shape.mesh.empty()) shape.mesh = model.name + ": " + model.links[link].name;
    const auto geometry =
        std::ranges::find(robot.links, model.links[link].name, &LinkGeometry::link);
    if (geometry == robot.links.end()) continue;
    const Transform& body_pose = world.body(bodies[b]).pose;
    const Eigen::Isometry3d body_in_world =
        Eigen::Translation3d(body_pose.translation.cast<double>()) *
        body_pose.rotation.cast<double>();
    const Eigen::Isometry3d link_in_body = body_in_world.inverse() * link_poses[link];
    TriangleMesh& mesh = meshes[b];
    const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const Vec3d& vertex : geometry->mesh.vertices)
      mesh.vertices.push_back(link_in_body * vertex);
    for (const Triangle& triangle : geometry->mesh.triangles) {
      mesh.triangles.push_back({triangle[0] + offset, triangle[1] + offset, triangle[2] + offset});
    }
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    meshes[b].name = out[first + b].mesh;
    out[first + b].body_mesh = std::make_shared<const TriangleMesh>(std::move(meshes[b]));
  }
}

}  // namespace

void append_recorded_robot(const World& world, RobotId robot, std::vector<BodyId>& bodies,
                           std::vector<RecordedJoint>& joints) {
  const std::span<const BodyId> own = world.robot_bodies(robot);
  bodies.insert(bodies.end(), own.begin(), own.end());
  const auto index = [&](BodyId body) -> std::optional<std::uint32_t> {
    if (body == BodyId{}) return std::nullopt;
    return static_cast<std::uint32_t>(std::ranges::find(bodies, body) - bodies.begin());
  };
  for (const JointId joint : world.robot_joints(robot)) {
    const JointDesc desc = world.joint(joint);
    joints.push_back({.type = desc.type,
                      .body_a = index(desc.body_a),
                      .body_b = index(desc.body_b),
                      .anchor_a = desc.anchor_a,
                      .anchor_b = desc.anchor_b});
  }
}

SceneRobots add_scene_robots(const Scene& scene, World& world) {
  SceneRobots added;
  for (std::size_t k = 0; k < scene.robots.size(); ++k) {
    const SceneRobot& robot = scene.robots[k];
    const std::string where = scene.name + ": /robots/" + std::to_string(k) + ": ";
    try {
      const auto from_scene = [&](const std::filesystem::path& path) {
        return scene.base_directory / path;
      };
      std::vector<RobotPackage> packages;
      for (const auto& [name, folder] : robot.packages) {
        packages.push_back({name, from_scene(folder)});
      }
      const LoadedRobot loaded =
          load_robot_files(from_scene(robot.urdf), from_scene(robot.spheres), packages,
                           robot.srdf ? std::optional(from_scene(*robot.srdf)) : std::nullopt);
      const RobotModel& model = loaded.model;
      const RobotId id = world.add_robot(model, {robot.orientation, robot.position},
                                         robot.fixed_base ? RobotBase::kFixed : RobotBase::kFree);
      if (!robot.configuration.empty()) world.set_robot_configuration(id, robot.configuration);
      if (!robot.targets.empty()) {
        if (robot.targets.size() != model.joints.size()) {
          throw Error("targets: " + std::to_string(robot.targets.size()) + " values for " +
                      std::to_string(model.joints.size()) + " joints");
        }
        check_joint_values(model, robot.targets, "targets");
        std::vector<RobotJointControl> controls(model.joints.size());
        for (std::size_t j = 0; j < controls.size(); ++j) {
          controls[j].mode = RobotControlMode::kPosition;
          controls[j].target_position = robot.targets[j];
        }
        world.set_robot_controls(id, controls);
      }
      added.robots.push_back(id);
      append_recorded_robot(world, id, added.bodies, added.joints);
      add_shapes(loaded.robot, world, id, added.shapes);
    } catch (const Error& error) {
      throw Error(where + error.what());
    }
  }
  return added;
}

bool recording_keeps_robots(const Scene& scene, const SceneRobots& robots,
                            std::uint32_t body_count) {
  if (body_count == scene.bodies.size() + robots.bodies.size()) return true;
  if (body_count == scene.bodies.size()) return false;
  throw Error("the recording has " + std::to_string(body_count) + " bodies but its scene " +
              std::to_string(scene.bodies.size()) +
              (robots.bodies.empty() ? std::string()
                                     : " and its robots " + std::to_string(robots.bodies.size())));
}

std::vector<RecordedJoint> recorded_joints(const Scene& scene, const SceneRobots& robots) {
  std::vector<RecordedJoint> joints = recorded_joints(scene);
  const auto after_scene = [&](std::optional<std::uint32_t> body) {
    if (body) *body += static_cast<std::uint32_t>(scene.bodies.size());
    return body;
  };
  for (RecordedJoint joint : robots.joints) {
    joint.body_a = after_scene(joint.body_a);
    joint.body_b = after_scene(joint.body_b);
    joints.push_back(joint);
  }
  return joints;
}

}  // namespace sphys::tools
