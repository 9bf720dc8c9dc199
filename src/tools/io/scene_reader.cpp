// The scene reader: a scene file's document, read strictly (json_document.h), checked key by key
// against the scene's manifest (scene_schema.h) into a Scene.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "input_file.h"
#include "io/scene_schema.h"
#include "io/setting_json.h"
#include "sphys/error.h"
#include "sphys/material.h"
#include "sphys/settings_table.h"
#include "sphys/tools/model.h"
#include "sphys/tools/scene_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// A quaternion whose length is within this of 1 is kept as written: dividing floats that already
// make a unit quaternion by their length would move their last bits, and a written scene must
// read back exactly. Anything further from 1 is normalised.
constexpr double kUnitTolerance = 1e-6;
// Every integer up to here is exact in a double, as a JSON number is read.
constexpr long long kMaxExactInteger = 9'007'199'254'740'992;  // 2^53

constexpr std::array<ArrayLimit, 3> kArrayLimits = {
    {{"/bodies", kMaxSceneBodies, "bodies; a scene holds at most that many"},
     {"/joints", kMaxSceneBodies, "joints; a scene holds at most as many as bodies"},
     {"/robots", kMaxSceneBodies, "robots; a scene holds at most as many as bodies"}}};

template <typename Enum, std::size_t N>
Enum read_choice(const JsonNode& node, const NameTable<Enum, N>& table) {
  std::array<std::string_view, N> names{};
  for (std::size_t i = 0; i < N; ++i) names[i] = table[i].second;
  return table[read_choice_index(node, names)].first;
}

std::string read_mesh(const JsonNode& node) {
  if (node.json().is_string() && node.json().get<std::string>() == kBunnyName) {
    return std::string(kBunnyName);
  }
  return read_existing_file(node, "a mesh file", InputKind::kMesh).string();
}

std::optional<std::size_t> read_triangles(const JsonNode& node) {
  if (node.json().is_null()) return std::nullopt;
  const long long triangles = read_integer(node, 0, kMaxTriangles);
  if (triangles > 0 && triangles < kMinTriangles) {
    node.fail("must be 0 (keep every triangle) or at least " + std::to_string(kMinTriangles) +
              ", got " + shown_value(node.json()));
  }
  return static_cast<std::size_t>(triangles);
}

TreeSpec read_tree(const JsonNode& node, const TreeSpec& start) {
  if (node.json().is_string()) {
    TreeSpec tree;
    tree.sph_file = read_existing_file(node, "a .sph file", InputKind::kSphereTree);
    return tree;
  }
  if (!node.json().is_object()) {
    fail_type(node, "an object {\"method\", \"branching\", \"depth\"} or the path of a .sph file");
  }
  check_keys(node, kTreeKeys);
  TreeSpec tree = start;
  tree.sph_file.reset();
  if (const auto method = node.find("method")) {
    const std::string name = read_string(*method);
    try {
      tree.method = parse_method(name);
    } catch (const Error& error) {
      method->fail(error.what());
    }
  }
  if (const auto branching = node.find("branching")) {
    tree.branching = static_cast<int>(read_integer(*branching, 2, 8));
  }
  if (const auto depth = node.find("depth")) {
    tree.depth = static_cast<int>(read_integer(*depth, 1, kMaxTreeDepth));
  }
  return tree;
}

// Divides by the length, computed without overflow or underflow for any finite input; nothing
// when the length is zero.
template <std::size_t N>
std::optional<std::array<double, N>> normalised(std::array<double, N> values) {
  double largest = 0.0;
  for (const double v : values) largest = std::max(largest, std::abs(v));
  if (largest == 0.0) return std::nullopt;
  double squares = 0.0;
  for (double& v : values) {
    v /= largest;
    squares += v * v;
  }
  const double length = std::sqrt(squares);
  for (double& v : values) v /= length;
  return values;
}

double length_of(const std::array<double, 4>& values) {
  double squares = 0.0;
  for (const double v : values) squares += v * v;
  return std::sqrt(squares);
}

Quat quaternion(double w, double x, double y, double z) {
  return {static_cast<float>(w), static_cast<float>(x), static_cast<float>(y),
          static_cast<float>(z)};
}

Quat rotation_about(const std::array<double, 3>& unit_axis, double degrees) {
  const double half = degrees * std::numbers::pi / 360.0;
  const double s = std::sin(half);
  return quaternion(std::cos(half), unit_axis[0] * s, unit_axis[1] * s, unit_axis[2] * s);
}

Quat read_orientation(const JsonNode& node) {
  check_keys(node, kOrientationKeys);
  const bool as_quaternion = has_any(node, kQuaternionKeys);
  const bool as_yaw = has_any(node, kYawKeys);
  const bool as_axis_angle = has_any(node, kAxisAngleKeys);
  constexpr std::string_view kForms =
      "{\"w\", \"x\", \"y\", \"z\"}, {\"yaw_degrees\"} or {\"axis\", \"angle_degrees\"}";
  if (int{as_quaternion} + int{as_yaw} + int{as_axis_angle} != 1) {
    node.fail((as_quaternion || as_yaw || as_axis_angle ? "mixes forms; give one of "
                                                        : "expected one of ") +
              std::string(kForms));
  }
  if (as_yaw) {
    // About +y, the up axis: counter-clockwise seen from above.
    return rotation_about({0.0, 1.0, 0.0}, read_number(node.child("yaw_degrees")));
  }
  if (as_axis_angle) {
    const JsonNode axis = node.required("axis", "an angle needs an axis");
    const JsonNode angle = node.required("angle_degrees", "an axis needs an angle");
    const auto unit_axis = normalised(read_triple(axis));
    if (!unit_axis) axis.fail("a zero-length axis has no direction");
    return rotation_about(*unit_axis, read_number(angle));
  }
  std::array<double, 4> wxyz{};
  for (std::size_t k = 0; k < 4; ++k) {
    const std::string key(kQuaternionKeys[k]);
    wxyz[k] = read_number(node.required(key, "a quaternion needs w, x, y and z"));
  }
  const auto unit = normalised(wxyz);
  if (!unit) node.fail("a zero-length quaternion is no rotation");
  const std::array<double, 4>& kept =
      std::abs(length_of(wxyz) - 1.0) <= kUnitTolerance ? wxyz : *unit;
  return quaternion(kept[0], kept[1], kept[2], kept[3]);
}

// Applies the keys of a body over `body`, which holds the defaults.
void read_body(const JsonNode& node, BodySpec& body) {
  check_keys(node, kBodyKeys);
  if (const auto n = node.find("mesh")) body.mesh = read_mesh(*n);
  if (const auto n = node.find("triangles")) body.triangles = read_triangles(*n);
  if (const auto n = node.find("size")) body.size = read_optional_physical(*n, kBodySizeRange);
  if (const auto n = node.find("sphere_tree")) body.tree = read_tree(*n, body.tree);
  if (const auto n = node.find("position")) {
    body.position = read_bounded_vec3(*n, kMaxCoordinate, "m");
  }
  if (const auto n = node.find("orientation")) body.orientation = read_orientation(*n);
  if (const auto n = node.find("linear_velocity")) {
    body.linear_velocity = read_bounded_vec3(*n, kMaxSpeed, "m/s");
  }
  if (const auto n = node.find("angular_velocity")) {
    body.angular_velocity = read_bounded_vec3(*n, kMaxSpeed, "rad/s");
  }
  if (const auto n = node.find("density")) body.density = read_physical(*n, kDensityRange);
  if (const auto n = node.find("mass")) body.mass = read_optional_physical(*n, kMassRange);
  if (const auto n = node.find("restitution")) body.restitution = read_fraction(*n);
  if (const auto n = node.find("friction")) body.friction = read_non_negative_single(*n);
  if (const auto n = node.find("static")) body.is_static = read_bool(*n);
}

// "defaults": the keys of a body but those set per body.
BodySpec read_defaults(const JsonNode& node) {
  check_keys(node, kBodyKeys);
  for (const std::string_view key : kPerBodyKeys) {
    if (const auto child = node.find(std::string(key))) {
      child->fail("set per body, not in \"defaults\"");
    }
  }
  BodySpec defaults;
  read_body(node, defaults);
  return defaults;
}

// The ground's own keys; its material is among the world's settings (read_settings).
GroundSpec read_ground(const JsonNode& node) {
  check_keys(node, ground_keys());
  GroundSpec ground;
  if (const auto n = node.find("type")) ground.kind = read_choice(*n, kGroundKinds);
  if (const auto n = node.find("height")) ground.height = read_bounded(*n, kMaxCoordinate, "m");
  if (const auto n = node.find("size")) ground.size = read_physical(*n, kGroundSizeRange);
  if (const auto n = node.find("thickness")) {
    ground.thickness = read_physical(*n, kGroundThicknessRange);
  }
  if (const auto n = node.find("depth")) {
    ground.depth = static_cast<int>(read_integer(*n, 1, kMaxGroundDepth));
  }
  return ground;
}

// An index into the scene's bodies.
std::size_t read_body_index(const JsonNode& node, std::size_t body_count) {
  const auto index = static_cast<std::size_t>(read_integer(node, 0, kMaxExactInteger));
  if (index >= body_count) {
    node.fail("no body " + std::to_string(index) + "; /bodies has " + std::to_string(body_count) +
              " (indices from 0)");
  }
  return index;
}

std::array<std::size_t, 2> read_body_pair(const JsonNode& node, std::size_t body_count) {
  if (!node.json().is_array()) fail_type(node, "an array of 2 body indices [i, j]");
  if (node.json().size() != 2) {
    node.fail("expected 2 body indices [i, j], got " + std::to_string(node.json().size()));
  }
  const std::array<std::size_t, 2> pair = {read_body_index(node.element(0), body_count),
                                           read_body_index(node.element(1), body_count)};
  if (pair[0] == pair[1]) {
    node.fail("a pair needs two different bodies, got " + shown_value(node.json()));
  }
  return pair;
}

// Each pair's material, defaulting to the mix of the two bodies' own. A pair given twice (in
// either order) is refused: the runtime would keep the last silently, hiding a slip.
std::vector<PairMaterialSpec> read_pair_materials(const JsonNode& node,
                                                  const std::vector<BodySpec>& bodies) {
  if (!node.json().is_array()) fail_type(node, "an array of pair materials");
  std::vector<PairMaterialSpec> pairs;
  for (std::size_t k = 0; k < node.json().size(); ++k) {
    const JsonNode entry = node.element(k);
    check_keys(entry, kPairMaterialKeys);
    const JsonNode bodies_node = entry.required("bodies", "a pair material names its two bodies");
    PairMaterialSpec pair;
    pair.bodies = read_body_pair(bodies_node, bodies.size());
    const auto same_pair = [&](const PairMaterialSpec& other) {
      return std::is_permutation(other.bodies.begin(), other.bodies.end(), pair.bodies.begin());
    };
    if (const auto earlier = std::find_if(pairs.begin(), pairs.end(), same_pair);
        earlier != pairs.end()) {
      bodies_node.fail("this pair already has a material, at /pair_materials/" +
                       std::to_string(earlier - pairs.begin()));
    }
    const BodySpec& a = bodies[pair.bodies[0]];
    const BodySpec& b = bodies[pair.bodies[1]];
    pair.material = {mix_friction(a.friction, b.friction),
                     mix_restitution(a.restitution, b.restitution)};
    if (const auto n = entry.find("friction")) {
      pair.material.friction = read_non_negative_single(*n);
    }
    if (const auto n = entry.find("restitution")) pair.material.restitution = read_fraction(*n);
    pairs.push_back(pair);
  }
  return pairs;
}

// A joint's body: an index into the scene's bodies, or null for the world.
std::optional<std::size_t> read_joint_body(const JsonNode& node, std::size_t body_count) {
  if (node.json().is_null()) return std::nullopt;
  return read_body_index(node, body_count);
}

// A direction: three numbers, not all zero (the world normalises it when the joint is added).
Vec3 read_axis(const JsonNode& node) {
  const Vec3 axis = read_vec3(node);
  if (!normalised(read_triple(node))) node.fail("a zero-length axis has no direction");
  return axis;
}

// An object of a joint's optional part: on when given, unless it says "enabled": false.
bool read_enabled(const JsonNode& node, std::span<const std::string_view> keys) {
  check_keys(node, keys);
  const auto enabled = node.find("enabled");
  return !enabled || read_bool(*enabled);
}

// The bounds are checked as the world checks them (World::add_joint): in order, and a distance's
// not negative, when the limit is on.
JointLimit read_joint_limit(const JsonNode& node, JointType type) {
  JointLimit limit;
  limit.enabled = read_enabled(node, kJointLimitKeys);
  const auto lower = node.find("lower");
  const auto upper = node.find("upper");
  if (lower) limit.lower = static_cast<float>(read_bounded(*lower, kMaxCoordinate, "rad or m"));
  if (upper) limit.upper = static_cast<float>(read_bounded(*upper, kMaxCoordinate, "rad or m"));
  if (!limit.enabled) return limit;
  if (lower && type == JointType::kDistance && limit.lower < 0.0f) {
    lower->fail("a distance joint's shortest length must not be negative, got " +
                shown_value(lower->json()));
  }
  if (limit.lower > limit.upper) {
    // As written: a bound left out is its default, 0.
    node.fail("lower " + (lower ? shown_value(lower->json()) : "0") + " > upper " +
              (upper ? shown_value(upper->json()) : "0"));
  }
  return limit;
}

JointMotor read_joint_motor(const JsonNode& node) {
  JointMotor motor;
  motor.enabled = read_enabled(node, kJointMotorKeys);
  if (const auto n = node.find("speed")) {
    motor.speed = static_cast<float>(read_bounded(*n, kMaxSpeed, "rad/s or m/s"));
  }
  if (const auto n = node.find("max_effort")) motor.max_effort = read_non_negative_single(*n);
  return motor;
}

JointSpring read_joint_spring(const JsonNode& node) {
  JointSpring spring;
  spring.enabled = read_enabled(node, kJointSpringKeys);
  if (const auto n = node.find("hertz")) spring.hertz = read_non_negative_single(*n);
  if (const auto n = node.find("damping_ratio")) {
    spring.damping_ratio = read_non_negative_single(*n);
  }
  if (const auto n = node.find("target")) {
    spring.target = static_cast<float>(read_bounded(*n, kMaxCoordinate, "rad or m"));
  }
  return spring;
}

JointCone read_joint_cone(const JsonNode& node) {
  JointCone cone;
  cone.enabled = read_enabled(node, kJointConeKeys);
  if (const auto n = node.find("angle")) {
    cone.angle = static_cast<float>(read_between(*n, 0.0, std::numbers::pi_v<float>));
  }
  return cone;
}

JointSpec read_joint(const JsonNode& node, std::size_t body_count) {
  check_keys(node, kJointKeys);
  JointSpec joint;
  JointDesc& desc = joint.desc;
  desc.type = read_choice(node.required("type", "a joint names its type"), kJointTypes);
  constexpr std::string_view kBodies = "a joint names its two bodies (null for the world)";
  joint.body_a = read_joint_body(node.required("body_a", kBodies), body_count);
  const JsonNode body_b = node.required("body_b", kBodies);
  joint.body_b = read_joint_body(body_b, body_count);
  if (!joint.body_a && !joint.body_b) body_b.fail("a joint needs a body; both are the world");
  if (joint.body_a == joint.body_b) {
    body_b.fail("the same body as body_a (" + std::to_string(*joint.body_a) + ")");
  }
  if (const auto n = node.find("anchor_a")) {
    desc.anchor_a = read_bounded_vec3(*n, kMaxCoordinate, "m");
  }
  if (const auto n = node.find("anchor_b")) {
    desc.anchor_b = read_bounded_vec3(*n, kMaxCoordinate, "m");
  }
  if (const auto n = node.find("axis_a")) desc.axis_a = read_axis(*n);
  if (const auto n = node.find("axis_b")) desc.axis_b = read_axis(*n);
  if (const auto n = node.find("limit")) desc.limit = read_joint_limit(*n, desc.type);
  if (const auto n = node.find("motor")) desc.motor = read_joint_motor(*n);
  if (const auto n = node.find("spring")) desc.spring = read_joint_spring(*n);
  if (const auto n = node.find("cone")) desc.cone = read_joint_cone(*n);
  if (const auto n = node.find("friction")) desc.friction = read_non_negative_single(*n);
  if (const auto n = node.find("length")) {
    desc.length = static_cast<float>(read_physical(*n, kJointLengthRange));
  }
  if (const auto n = node.find("collide_connected")) desc.collide_connected = read_bool(*n);
  return joint;
}

std::vector<JointSpec> read_joints(const JsonNode& node, std::size_t body_count) {
  if (!node.json().is_array()) fail_type(node, "an array of joints");
  std::vector<JointSpec> joints;
  for (std::size_t k = 0; k < node.json().size(); ++k) {
    joints.push_back(read_joint(node.element(k), body_count));
  }
  return joints;
}

// Joint values, one per joint (the model's count is checked when the robot is added).
std::vector<double> read_joint_values(const JsonNode& node) {
  if (!node.json().is_array()) fail_type(node, "an array of joint values (rad or m)");
  std::vector<double> values;
  for (std::size_t k = 0; k < node.json().size(); ++k) {
    values.push_back(read_bounded(node.element(k), kMaxCoordinate, "rad or m"));
  }
  return values;
}

SceneRobot read_robot(const JsonNode& node) {
  check_keys(node, kRobotKeys);
  SceneRobot robot;
  robot.urdf = read_existing_file(node.required("urdf", "a robot names its URDF"), "a URDF",
                                  InputKind::kRobot);
  robot.spheres = read_existing_file(node.required("spheres", "a robot names its spheres' file"),
                                     "the spheres `sphys spherize` wrote", InputKind::kRobot);
  if (const auto n = node.find("srdf"); n && !n->json().is_null()) {
    robot.srdf = read_existing_file(*n, "an SRDF", InputKind::kRobot);
  }
  if (const auto n = node.find("packages")) {
    if (!n->json().is_object()) fail_type(*n, "an object of package folders by name");
    for (const auto& item : n->json().items()) {
      const JsonNode folder = n->child(item.key());
      const fs::path written = read_string(folder);
      if (!fs::is_directory(folder.source().base_directory / written)) {
        folder.fail("no such folder: " + (folder.source().base_directory / written).string());
      }
      robot.packages[item.key()] = written;
    }
  }
  if (const auto n = node.find("position")) {
    robot.position = read_bounded_vec3(*n, kMaxCoordinate, "m");
  }
  if (const auto n = node.find("orientation")) robot.orientation = read_orientation(*n);
  if (const auto n = node.find("fixed_base")) robot.fixed_base = read_bool(*n);
  if (const auto n = node.find("configuration")) robot.configuration = read_joint_values(*n);
  if (const auto n = node.find("targets")) robot.targets = read_joint_values(*n);
  return robot;
}

std::vector<SceneRobot> read_robots(const JsonNode& node) {
  if (!node.json().is_array()) fail_type(node, "an array of robots");
  std::vector<SceneRobot> robots;
  for (std::size_t k = 0; k < node.json().size(); ++k) {
    robots.push_back(read_robot(node.element(k)));
  }
  return robots;
}

void read_header(const JsonNode& root) {
  const JsonNode format =
      root.required("format", "a scene file starts with \"format\": \"sphys-scene\"");
  if (!format.json().is_string() || format.json().get<std::string>() != kSceneFormat) {
    fail_type(format, "\"" + std::string(kSceneFormat) + "\"");
  }
  const JsonNode version = root.required("version", "this build reads \"version\": 1");
  if (read_number(version) != static_cast<double>(kSceneVersion)) {
    version.fail("unsupported version " + shown_value(version.json()) +
                 "; this build reads version " + std::to_string(kSceneVersion));
  }
}

Scene read_scene(const Json& document, const fs::path& name) {
  const JsonSource source{name, name.parent_path()};
  if (!document.is_object()) {
    throw Error::in_file(name,
                         "expected a JSON object at the top level, got " + described(document));
  }
  const JsonNode root(document, "", source);
  read_header(root);
  refuse_removed_settings(root, "");
  check_keys(root, scene_keys());

  Scene scene;
  scene.name = name.filename().string();
  scene.base_directory = source.base_directory;
  if (const auto n = root.find("time_step")) {
    scene.time_step = read_physical(*n, kTimeStepRange);
  }
  if (const auto n = root.find("frames")) {
    scene.frames = static_cast<int>(read_integer(*n, 1, kMaxFrames));
  }
  WorldSettings settings = world_settings(scene);
  read_settings(root, "", settings);
  if (const auto n = root.find("solver")) read_settings_object(*n, "solver", settings);
  if (const auto n = root.find("sleep")) read_settings_object(*n, "sleep", settings);
  if (const auto n = root.find("ground")) {
    scene.ground = read_ground(*n);
    read_settings(*n, "ground", settings);
  }
  set_world_settings(scene, settings);

  const BodySpec defaults =
      root.find("defaults") ? read_defaults(root.child("defaults")) : BodySpec{};
  const JsonNode bodies =
      root.required("bodies", "a scene lists its bodies (the list may be empty)");
  if (!bodies.json().is_array()) fail_type(bodies, "an array of bodies");
  for (std::size_t i = 0; i < bodies.json().size(); ++i) {
    BodySpec body = defaults;
    read_body(bodies.element(i), body);
    scene.bodies.push_back(std::move(body));
  }
  if (const auto n = root.find("pair_materials")) {
    scene.pair_materials = read_pair_materials(*n, scene.bodies);
  }
  if (const auto n = root.find("joints")) scene.joints = read_joints(*n, scene.bodies.size());
  if (const auto n = root.find("robots")) scene.robots = read_robots(*n);
  return scene;
}

}  // namespace

Scene parse_scene(std::string_view json_text, const fs::path& name) {
  return read_scene(parse_json(json_text, name, kArrayLimits), name);
}

Scene parse_recorded_scene(std::string_view json_text, const fs::path& name) {
  Json document = parse_json(json_text, name, kArrayLimits);
  // A recording made before a setting was removed carries it, written out with all the others: it
  // says how the recording was made, and replaying or exporting needs the shapes and the poses.
  if (document.is_object() && document.contains("solver") && document["solver"].is_object()) {
    Json& solver = document["solver"];
    for (auto item = solver.begin(); item != solver.end();) {
      item =
          removed_setting("solver." + item.key()) != nullptr ? solver.erase(item) : std::next(item);
    }
  }
  return read_scene(document, name);
}

Scene read_scene_file(const fs::path& path) {
  return parse_scene(read_input_file(path, InputKind::kScene), path);
}

}  // namespace sphys::tools
