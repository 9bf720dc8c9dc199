// The scene writer: every key of the scene's manifest (scene_schema.h) written out, in the order
// of docs/scenes.md, so that the reader gets back the same scene bit for bit.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "io/scene_schema.h"
#include "io/setting_json.h"
#include "sphys/settings_table.h"
#include "sphys/tools/model.h"
#include "sphys/tools/scene_file.h"

namespace sphys::tools {
namespace {

// Floats are written in their shortest decimal form (shortest_double), so that 0.3f is written
// "0.3" rather than "0.30000001192092896" and reads back bit for bit.
Json vec3_json(const Vec3& v) {
  return Json::array({shortest_double(v.x()), shortest_double(v.y()), shortest_double(v.z())});
}

Json quaternion_json(const Quat& q) {
  return {{"w", shortest_double(q.w())},
          {"x", shortest_double(q.x())},
          {"y", shortest_double(q.y())},
          {"z", shortest_double(q.z())}};
}

template <typename T>
Json optional_json(const std::optional<T>& value) {
  return value ? Json(*value) : Json(nullptr);
}

Json tree_json(const TreeSpec& tree) {
  if (tree.sph_file) return tree.sph_file->generic_string();
  Json out = Json::object();
  out["method"] = method_name(tree.method);
  out["branching"] = tree.branching;
  out["depth"] = tree.depth;
  return out;
}

Json body_json(const BodySpec& body) {
  Json out = Json::object();
  out["mesh"] = body.mesh;
  out["triangles"] = optional_json(body.triangles);
  out["size"] = optional_json(body.size);
  out["sphere_tree"] = tree_json(body.tree);
  out["position"] = vec3_json(body.position);
  out["orientation"] = quaternion_json(body.orientation);
  out["linear_velocity"] = vec3_json(body.linear_velocity);
  out["angular_velocity"] = vec3_json(body.angular_velocity);
  out["density"] = body.density;
  out["mass"] = optional_json(body.mass);
  out["restitution"] = shortest_double(body.restitution);
  out["friction"] = shortest_double(body.friction);
  out["static"] = body.is_static;
  return out;
}

Json ground_json(const GroundSpec& ground) {
  Json out = Json::object();
  out["type"] = name_of(ground.kind, kGroundKinds);
  out["height"] = ground.height;
  out["size"] = ground.size;
  out["thickness"] = ground.thickness;
  out["depth"] = ground.depth;
  return out;
}

Json pair_material_json(const PairMaterialSpec& pair) {
  return {{"bodies", Json::array({pair.bodies[0], pair.bodies[1]})},
          {"friction", shortest_double(pair.material.friction)},
          {"restitution", shortest_double(pair.material.restitution)}};
}

Json joint_json(const JointSpec& joint) {
  const JointDesc& d = joint.desc;
  Json out = Json::object();
  out["type"] = name_of(d.type, kJointTypes);
  out["body_a"] = optional_json(joint.body_a);
  out["body_b"] = optional_json(joint.body_b);
  out["anchor_a"] = vec3_json(d.anchor_a);
  out["anchor_b"] = vec3_json(d.anchor_b);
  out["axis_a"] = vec3_json(d.axis_a);
  out["axis_b"] = vec3_json(d.axis_b);
  out["limit"] = {{"enabled", d.limit.enabled},
                  {"lower", shortest_double(d.limit.lower)},
                  {"upper", shortest_double(d.limit.upper)}};
  out["motor"] = {{"enabled", d.motor.enabled},
                  {"speed", shortest_double(d.motor.speed)},
                  {"max_effort", shortest_double(d.motor.max_effort)}};
  out["spring"] = {{"enabled", d.spring.enabled},
                   {"hertz", shortest_double(d.spring.hertz)},
                   {"damping_ratio", shortest_double(d.spring.damping_ratio)},
                   {"target", shortest_double(d.spring.target)}};
  out["cone"] = {{"enabled", d.cone.enabled}, {"angle", shortest_double(d.cone.angle)}};
  out["friction"] = shortest_double(d.friction);
  out["length"] = shortest_double(d.length);
  out["collide_connected"] = d.collide_connected;
  return out;
}

Json robot_json(const SceneRobot& robot) {
  Json out = Json::object();
  out["urdf"] = robot.urdf.generic_string();
  out["spheres"] = robot.spheres.generic_string();
  out["srdf"] = robot.srdf ? Json(robot.srdf->generic_string()) : Json(nullptr);
  Json packages = Json::object();
  for (const auto& [name, folder] : robot.packages) packages[name] = folder.generic_string();
  out["packages"] = std::move(packages);
  out["position"] = vec3_json(robot.position);
  out["orientation"] = quaternion_json(robot.orientation);
  out["fixed_base"] = robot.fixed_base;
  out["configuration"] = robot.configuration;
  out["targets"] = robot.targets;
  return out;
}

}  // namespace

std::string scene_to_json(const Scene& scene) {
  Json out = Json::object();
  out["format"] = kSceneFormat;
  out["version"] = kSceneVersion;
  out["time_step"] = scene.time_step;
  out["frames"] = scene.frames;
  const WorldSettings settings = world_settings(scene);
  out.update(settings_json("", settings));
  out["solver"] = settings_json("solver", settings);
  out["sleep"] = settings_json("sleep", settings);
  out["ground"] = ground_json(scene.ground);
  out["ground"].update(settings_json("ground", settings));
  Json bodies = Json::array();
  for (const BodySpec& body : scene.bodies) bodies.push_back(body_json(body));
  out["bodies"] = std::move(bodies);
  Json pairs = Json::array();
  for (const PairMaterialSpec& pair : scene.pair_materials) {
    pairs.push_back(pair_material_json(pair));
  }
  out["pair_materials"] = std::move(pairs);
  Json joints = Json::array();
  for (const JointSpec& joint : scene.joints) joints.push_back(joint_json(joint));
  out["joints"] = std::move(joints);
  Json robots = Json::array();
  for (const SceneRobot& robot : scene.robots) robots.push_back(robot_json(robot));
  out["robots"] = std::move(robots);
  return out.dump(2) + "\n";
}

std::string recorded_scene_json(Scene scene) {
  const auto absolute = [&](const std::filesystem::path& path) {
    return std::filesystem::absolute(path.is_absolute() ? path : scene.base_directory / path);
  };
  for (BodySpec& body : scene.bodies) {
    if (body.mesh != kBunnyName) body.mesh = absolute(body.mesh).string();
    if (body.tree.sph_file) body.tree.sph_file = absolute(*body.tree.sph_file);
  }
  for (SceneRobot& robot : scene.robots) {
    robot.urdf = absolute(robot.urdf);
    robot.spheres = absolute(robot.spheres);
    if (robot.srdf) robot.srdf = absolute(*robot.srdf);
    for (auto& [name, folder] : robot.packages) folder = absolute(folder);
  }
  return scene_to_json(scene);
}

std::vector<RecordedJoint> recorded_joints(const Scene& scene) {
  std::vector<RecordedJoint> joints;
  const auto index = [](const std::optional<std::size_t>& body) -> std::optional<std::uint32_t> {
    if (!body) return std::nullopt;
    return static_cast<std::uint32_t>(*body);
  };
  for (const JointSpec& joint : scene.joints) {
    joints.push_back({.type = joint.desc.type,
                      .body_a = index(joint.body_a),
                      .body_b = index(joint.body_b),
                      .anchor_a = joint.desc.anchor_a,
                      .anchor_b = joint.desc.anchor_b});
  }
  return joints;
}

}  // namespace sphys::tools
