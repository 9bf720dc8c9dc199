#include "sphys/tools/scene_file.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sphys/error.h"
#include "sphys/setting_limits.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using testing::AllOf;
using testing::Eq;
using testing::HasSubstr;
using testing::Not;
using testing::StartsWith;

constexpr std::string_view kHeader = R"("format": "sphys-scene", "version": 1)";

// A scene file's text: the header, then `members` (JSON object members, comma-separated).
std::string scene_text(std::string_view members) {
  return "{" + std::string(kHeader) + ", " + std::string(members) + "}";
}

// The message of the Error that parsing `text` throws.
std::string parse_error(std::string_view text, const fs::path& name = "scene.json") {
  try {
    (void)parse_scene(text, name);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

std::string read_error(const fs::path& path) {
  try {
    (void)read_scene_file(path);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

std::uint32_t bits(float value) { return std::bit_cast<std::uint32_t>(value); }
std::uint64_t bits(double value) { return std::bit_cast<std::uint64_t>(value); }

void expect_same(const Vec3& a, const Vec3& b, std::string_view what) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(a[k]), bits(b[k])) << what << "[" << k << "]";
}

void expect_same(const std::optional<double>& a, const std::optional<double>& b,
                 std::string_view what) {
  ASSERT_EQ(a.has_value(), b.has_value()) << what;
  if (a) {
    EXPECT_EQ(bits(*a), bits(*b)) << what;
  }
}

// Field by field, every number bit for bit.
void expect_same_body(const BodySpec& a, const BodySpec& b) {
  EXPECT_EQ(a.mesh, b.mesh);
  EXPECT_EQ(a.triangles, b.triangles);
  expect_same(a.size, b.size, "size");
  EXPECT_EQ(a.tree.sph_file, b.tree.sph_file);
  EXPECT_EQ(a.tree.method, b.tree.method);
  EXPECT_EQ(a.tree.branching, b.tree.branching);
  EXPECT_EQ(a.tree.depth, b.tree.depth);
  expect_same(a.position, b.position, "position");
  EXPECT_EQ(bits(a.orientation.w()), bits(b.orientation.w()));
  expect_same(a.orientation.vec(), b.orientation.vec(), "orientation");
  expect_same(a.linear_velocity, b.linear_velocity, "linear_velocity");
  expect_same(a.angular_velocity, b.angular_velocity, "angular_velocity");
  EXPECT_EQ(bits(a.density), bits(b.density));
  expect_same(a.mass, b.mass, "mass");
  EXPECT_EQ(bits(a.restitution), bits(b.restitution));
  EXPECT_EQ(bits(a.friction), bits(b.friction));
  EXPECT_EQ(a.is_static, b.is_static);
}

void expect_same_solver(const SolverSettings& a, const SolverSettings& b) {
  EXPECT_EQ(a.soft_substeps, b.soft_substeps);
  EXPECT_EQ(bits(a.contact_hertz), bits(b.contact_hertz));
  EXPECT_EQ(bits(a.contact_damping_ratio), bits(b.contact_damping_ratio));
  EXPECT_EQ(a.warm_starting, b.warm_starting);
  EXPECT_EQ(bits(a.rolling_resistance), bits(b.rolling_resistance));
  EXPECT_EQ(bits(a.reuse_distance), bits(b.reuse_distance));
  EXPECT_EQ(bits(a.restitution_threshold), bits(b.restitution_threshold));
  EXPECT_EQ(bits(a.linear_slop), bits(b.linear_slop));
  EXPECT_EQ(bits(a.max_correction_speed), bits(b.max_correction_speed));
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_EQ(a.manifold_points, b.manifold_points);
  EXPECT_EQ(bits(a.fast_pair_reach), bits(b.fast_pair_reach));
  EXPECT_EQ(bits(a.contact_margin), bits(b.contact_margin));
  EXPECT_EQ(a.speculative_contacts, b.speculative_contacts);
}

void expect_same_sleep(const SleepSettings& a, const SleepSettings& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(bits(a.speed), bits(b.speed));
  EXPECT_EQ(bits(a.time), bits(b.time));
}

void expect_same_pairs(const std::vector<PairMaterialSpec>& a,
                       const std::vector<PairMaterialSpec>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].bodies, b[k].bodies) << "pair " << k;
    EXPECT_EQ(bits(a[k].material.friction), bits(b[k].material.friction)) << "pair " << k;
    EXPECT_EQ(bits(a[k].material.restitution), bits(b[k].material.restitution)) << "pair " << k;
  }
}

void expect_same_joints(const std::vector<JointSpec>& a, const std::vector<JointSpec>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE("joint " + std::to_string(k));
    const JointDesc& x = a[k].desc;
    const JointDesc& y = b[k].desc;
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(a[k].body_a, b[k].body_a);
    EXPECT_EQ(a[k].body_b, b[k].body_b);
    expect_same(x.anchor_a, y.anchor_a, "anchor_a");
    expect_same(x.anchor_b, y.anchor_b, "anchor_b");
    expect_same(x.axis_a, y.axis_a, "axis_a");
    expect_same(x.axis_b, y.axis_b, "axis_b");
    EXPECT_EQ(x.limit.enabled, y.limit.enabled);
    EXPECT_EQ(bits(x.limit.lower), bits(y.limit.lower));
    EXPECT_EQ(bits(x.limit.upper), bits(y.limit.upper));
    EXPECT_EQ(x.motor.enabled, y.motor.enabled);
    EXPECT_EQ(bits(x.motor.speed), bits(y.motor.speed));
    EXPECT_EQ(bits(x.motor.max_effort), bits(y.motor.max_effort));
    EXPECT_EQ(x.spring.enabled, y.spring.enabled);
    EXPECT_EQ(bits(x.spring.hertz), bits(y.spring.hertz));
    EXPECT_EQ(bits(x.spring.damping_ratio), bits(y.spring.damping_ratio));
    EXPECT_EQ(bits(x.spring.target), bits(y.spring.target));
    EXPECT_EQ(x.cone.enabled, y.cone.enabled);
    EXPECT_EQ(bits(x.cone.angle), bits(y.cone.angle));
    EXPECT_EQ(bits(x.friction), bits(y.friction));
    EXPECT_EQ(bits(x.length), bits(y.length));
    EXPECT_EQ(x.collide_connected, y.collide_connected);
  }
}

void expect_same_robots(const std::vector<SceneRobot>& a, const std::vector<SceneRobot>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE("robot " + std::to_string(k));
    EXPECT_EQ(a[k].urdf, b[k].urdf);
    EXPECT_EQ(a[k].spheres, b[k].spheres);
    EXPECT_EQ(a[k].srdf, b[k].srdf);
    EXPECT_EQ(a[k].packages, b[k].packages);
    expect_same(a[k].position, b[k].position, "position");
    EXPECT_EQ(a[k].orientation.coeffs(), b[k].orientation.coeffs());
    EXPECT_EQ(a[k].fixed_base, b[k].fixed_base);
    EXPECT_EQ(a[k].configuration, b[k].configuration);
    EXPECT_EQ(a[k].targets, b[k].targets);
  }
}

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.base_directory, b.base_directory);
  expect_same(a.gravity, b.gravity, "gravity");
  EXPECT_EQ(bits(a.time_step), bits(b.time_step));
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.response, b.response);
  EXPECT_EQ(a.paper_passes, b.paper_passes);
  EXPECT_EQ(a.collision_passes, b.collision_passes);
  EXPECT_EQ(a.max_collision_passes, b.max_collision_passes);
  EXPECT_EQ(bits(a.collision_pass_travel), bits(b.collision_pass_travel));
  expect_same_solver(a.solver, b.solver);
  expect_same_sleep(a.sleep, b.sleep);
  expect_same_pairs(a.pair_materials, b.pair_materials);
  expect_same_joints(a.joints, b.joints);
  expect_same_robots(a.robots, b.robots);
  EXPECT_EQ(a.ground.kind, b.ground.kind);
  EXPECT_EQ(bits(a.ground.height), bits(b.ground.height));
  EXPECT_EQ(bits(a.ground.size), bits(b.ground.size));
  EXPECT_EQ(bits(a.ground.thickness), bits(b.ground.thickness));
  EXPECT_EQ(a.ground.depth, b.ground.depth);
  EXPECT_EQ(bits(a.ground.restitution), bits(b.ground.restitution));
  EXPECT_EQ(bits(a.ground.friction), bits(b.ground.friction));
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    SCOPED_TRACE("body " + std::to_string(i));
    expect_same_body(a.bodies[i], b.bodies[i]);
  }
}

void expect_rotation(const Quat& q, const Vec3& from, const Vec3& to) {
  const Vec3 rotated = q * from;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rotated[k], to[k], 1e-6f) << "component " << k;
}

// Every key of the format, each with a value other than its default.
constexpr std::string_view kFullScene = R"({
  "format": "sphys-scene",
  "version": 1,
  "gravity": [0.5, -3.7, 0.25],
  "time_step": 0.005,
  "frames": 1200,
  "response": "paper",
  "paper_passes": 7,
  "contacts": "all",
  "collision_passes": 4,
  "max_collision_passes": 12,
  "collision_pass_travel": 0.25,
  "solver": {"soft_substeps": 7, "contact_hertz": 45, "contact_damping_ratio": 2.5,
             "warm_starting": false, "restitution_threshold": 0.5, "linear_slop": 0.01,
             "max_correction_speed": 2, "manifold_points": 6, "fast_pair_reach": 0.25,
             "contact_margin": 0.05,
             "rolling_resistance": 0.02, "reuse_distance": 0.001,
             "speculative_contacts": false},
  "sleep": {"enabled": false, "speed": 0.1, "time": 2},
  "ground": {"type": "plane", "height": -1.5, "size": 20, "thickness": 0.75, "depth": 4,
             "restitution": 0.8, "friction": 0.9},
  "defaults": {"density": 500, "friction": 0.2},
  "bodies": [
    {"mesh": "meshes/box.obj", "triangles": 0, "size": null,
     "sphere_tree": {"method": "octree", "branching": 4, "depth": 2},
     "position": [1, 2, 3], "orientation": {"w": 0, "x": 0, "y": 0, "z": 1},
     "linear_velocity": [4, 5, 6], "angular_velocity": [-1, 0.5, 2], "density": 250,
     "mass": 12.5, "restitution": 0.1, "friction": 0.7, "static": true},
    {"mesh": "bunny", "triangles": 800, "size": 2.5, "sphere_tree": "trees/bunny.sph"}
  ],
  "pair_materials": [{"bodies": [1, 0], "friction": 1.25, "restitution": 0.05}],
  "joints": [
    {"type": "slider", "body_a": null, "body_b": 1, "anchor_a": [0, 1, 0],
     "anchor_b": [0.5, 0, 0], "axis_a": [0, 1, 0], "axis_b": [0, 0, 2],
     "limit": {"enabled": true, "lower": -0.5, "upper": 1.5},
     "motor": {"enabled": false, "speed": 2, "max_effort": 30},
     "spring": {"hertz": 4, "damping_ratio": 0.7, "target": 0.25},
     "cone": {"angle": 0.5}, "friction": 3.5, "length": 2.5, "collide_connected": true}
  ],
  "robots": [
    {"urdf": "robot/arm.urdf", "spheres": "robot/arm.yml", "srdf": "robot/arm.srdf",
     "packages": {"arm_pkg": "robot"}, "position": [0.5, 0, -1],
     "orientation": {"yaw_degrees": 90}, "fixed_base": false, "configuration": [0.25, -0.5],
     "targets": [1, 0.125]}
  ]
})";

class SceneFileOnDisk : public testing::Test {
 protected:
  SceneFileOnDisk() {
    fs::create_directories(dir_.path() / "meshes");
    fs::create_directories(dir_.path() / "trees");
    // Only their existence is checked when a scene is read.
    dir_.write("meshes/box.obj", "v 0 0 0\n");
    dir_.write("trees/bunny.sph", "1 2\n0 0 0 1 1\n");
    fs::create_directories(dir_.path() / "robot");
    for (const char* file : {"robot/arm.urdf", "robot/arm.yml", "robot/arm.srdf"}) {
      dir_.write(file, "<robot/>\n");
    }
  }

  [[nodiscard]] fs::path scene_path() const { return dir_.path() / "scene.json"; }

  test::TempDir dir_;
};

TEST_F(SceneFileOnDisk, FullSceneReadsEveryValue) {
  const Scene scene = read_scene_file(dir_.write("scene.json", kFullScene));
  EXPECT_EQ(scene.name, "scene.json");
  EXPECT_EQ(scene.base_directory, dir_.path());
  expect_same(scene.gravity, Vec3(0.5f, -3.7f, 0.25f), "gravity");
  EXPECT_EQ(scene.time_step, 0.005);
  EXPECT_EQ(scene.frames, 1200);
  EXPECT_EQ(scene.response, ResponseMode::kPaper);
  EXPECT_EQ(scene.paper_passes, 7);
  EXPECT_EQ(scene.collision_passes, 4);
  EXPECT_EQ(scene.max_collision_passes, 12);
  EXPECT_EQ(scene.collision_pass_travel, 0.25f);
  SolverSettings solver;
  solver.soft_substeps = 7;
  solver.contact_hertz = 45.0f;
  solver.contact_damping_ratio = 2.5f;
  solver.warm_starting = false;
  solver.restitution_threshold = 0.5f;
  solver.linear_slop = 0.01f;
  solver.max_correction_speed = 2.0f;
  solver.rolling_resistance = 0.02f;
  solver.reuse_distance = 0.001f;
  solver.contacts = ContactSet::kAll;
  solver.manifold_points = 6;
  solver.fast_pair_reach = 0.25f;
  solver.contact_margin = 0.05f;
  solver.speculative_contacts = false;
  expect_same_solver(scene.solver, solver);
  expect_same_sleep(scene.sleep, {.enabled = false, .speed = 0.1f, .time = 2.0f});
  expect_same_pairs(scene.pair_materials, {{.bodies = {1, 0}, .material = {1.25f, 0.05f}}});
  JointSpec slider{.body_a = std::nullopt, .body_b = 1, .desc = {}};
  slider.desc.type = JointType::kSlider;
  slider.desc.anchor_a = Vec3(0.0f, 1.0f, 0.0f);
  slider.desc.anchor_b = Vec3(0.5f, 0.0f, 0.0f);
  slider.desc.axis_a = Vec3(0.0f, 1.0f, 0.0f);
  slider.desc.axis_b = Vec3(0.0f, 0.0f, 2.0f);  // as written: the world normalises it
  slider.desc.limit = {.enabled = true, .lower = -0.5f, .upper = 1.5f};
  slider.desc.motor = {.enabled = false, .speed = 2.0f, .max_effort = 30.0f};
  // An object given is on unless it says otherwise.
  slider.desc.spring = {.enabled = true, .hertz = 4.0f, .damping_ratio = 0.7f, .target = 0.25f};
  slider.desc.cone = {.enabled = true, .angle = 0.5f};
  slider.desc.friction = 3.5f;
  slider.desc.length = 2.5f;
  slider.desc.collide_connected = true;
  expect_same_joints(scene.joints, {slider});
  ASSERT_EQ(scene.robots.size(), 1U);
  const SceneRobot& robot = scene.robots.front();
  EXPECT_EQ(robot.urdf, "robot/arm.urdf");
  EXPECT_EQ(robot.spheres, "robot/arm.yml");
  EXPECT_EQ(robot.srdf, std::optional<fs::path>("robot/arm.srdf"));
  EXPECT_EQ(robot.packages, (std::map<std::string, fs::path>{{"arm_pkg", "robot"}}));
  expect_same(robot.position, Vec3(0.5f, 0.0f, -1.0f), "robot position");
  expect_rotation(robot.orientation, Vec3::UnitX(), -Vec3::UnitZ());
  EXPECT_FALSE(robot.fixed_base);
  EXPECT_EQ(robot.configuration, (std::vector<double>{0.25, -0.5}));
  EXPECT_EQ(robot.targets, (std::vector<double>{1.0, 0.125}));
  EXPECT_EQ(scene.ground.kind, GroundSpec::Kind::kPlane);
  EXPECT_EQ(scene.ground.height, -1.5);
  EXPECT_EQ(scene.ground.size, 20.0);
  EXPECT_EQ(scene.ground.thickness, 0.75);
  EXPECT_EQ(scene.ground.depth, 4);
  EXPECT_EQ(scene.ground.restitution, 0.8f);
  EXPECT_EQ(scene.ground.friction, 0.9f);
  ASSERT_EQ(scene.bodies.size(), 2U);

  const BodySpec& box = scene.bodies[0];
  EXPECT_EQ(box.mesh, "meshes/box.obj");
  EXPECT_EQ(box.triangles, std::optional<std::size_t>(0));
  EXPECT_EQ(box.size, std::nullopt);
  EXPECT_EQ(box.tree.sph_file, std::nullopt);
  EXPECT_EQ(box.tree.method, BuildMethod::Octree);
  EXPECT_EQ(box.tree.branching, 4);
  EXPECT_EQ(box.tree.depth, 2);
  expect_same(box.position, Vec3(1.0f, 2.0f, 3.0f), "position");
  EXPECT_EQ(box.orientation.coeffs(), Quat(0.0f, 0.0f, 0.0f, 1.0f).coeffs());
  expect_same(box.linear_velocity, Vec3(4.0f, 5.0f, 6.0f), "linear_velocity");
  expect_same(box.angular_velocity, Vec3(-1.0f, 0.5f, 2.0f), "angular_velocity");
  EXPECT_EQ(box.density, 250.0);
  EXPECT_EQ(box.mass, std::optional<double>(12.5));
  EXPECT_EQ(box.restitution, 0.1f);
  EXPECT_EQ(box.friction, 0.7f);
  EXPECT_TRUE(box.is_static);

  // The second body keeps the defaults' density and friction and BodySpec's other defaults.
  const BodySpec& bunny = scene.bodies[1];
  EXPECT_EQ(bunny.mesh, "bunny");
  EXPECT_EQ(bunny.triangles, std::optional<std::size_t>(800));
  EXPECT_EQ(bunny.size, std::optional<double>(2.5));
  EXPECT_EQ(bunny.tree.sph_file, std::optional<fs::path>("trees/bunny.sph"));
  EXPECT_EQ(bunny.density, 500.0);
  EXPECT_EQ(bunny.friction, 0.2f);
  BodySpec expected;
  expected.mesh = "bunny";
  expected.triangles = 800;
  expected.size = 2.5;
  expected.tree.sph_file = "trees/bunny.sph";
  expected.density = 500.0;
  expected.friction = 0.2f;
  expect_same_body(bunny, expected);
}

TEST(SceneFile, SmallestSceneTakesEveryDefault) {
  const Scene scene = parse_scene(scene_text(R"("bodies": [{}])"), "dir/scene.json");
  Scene expected;
  expected.name = "scene.json";
  expected.base_directory = "dir";
  expected.bodies.emplace_back();
  expect_same_scene(scene, expected);
  // The header and an empty body list make a scene too.
  EXPECT_TRUE(parse_scene(scene_text(R"("bodies": [])"), "s.json").bodies.empty());
}

TEST(SceneFile, WorldSettingsLeftOutAreTheRuntimesDefaults) {
  const Scene scene = parse_scene(scene_text(R"("bodies": [{}])"), "s.json");
  const WorldSettings runtime;
  EXPECT_EQ(scene.response, ResponseMode::kPlausible);
  EXPECT_EQ(scene.response, runtime.response);
  EXPECT_EQ(scene.paper_passes, static_cast<int>(runtime.paper_passes));
  EXPECT_EQ(scene.collision_passes, static_cast<int>(runtime.collision_passes));
  EXPECT_EQ(scene.solver.contacts, ContactSet::kReduced);
  expect_same_solver(scene.solver, runtime.solver);
  expect_same_sleep(scene.sleep, runtime.sleep);
  expect_same(scene.gravity, runtime.gravity, "gravity");
  EXPECT_EQ(scene.ground.restitution, runtime.ground_restitution);
  EXPECT_EQ(scene.ground.friction, runtime.ground_friction);
  EXPECT_TRUE(scene.pair_materials.empty());
}

TEST(SceneFile, SolverAndSleepObjectsSetOnlyTheKeysTheyHave) {
  const Scene scene = parse_scene(scene_text(R"("contacts": "all", "collision_passes": 64,
      "solver": {"manifold_points": 8}, "sleep": {"time": 0}, "bodies": [])"),
                                  "s.json");
  EXPECT_EQ(scene.collision_passes, 64);
  SolverSettings solver;
  solver.contacts = ContactSet::kAll;
  solver.manifold_points = 8;
  expect_same_solver(scene.solver, solver);
  expect_same_sleep(scene.sleep, {.enabled = true, .speed = SleepSettings{}.speed, .time = 0.0f});
}

// A recording made before the sequential-impulse solver was removed embeds its settings: the
// scene reads back without them, the others kept; a scene file naming them is refused (below).
TEST(SceneFile, ARecordedSceneDropsTheRemovedSolverSettings) {
  const std::string text = scene_text(R"("solver": {"method": "sequential_impulses",
      "velocity_iterations": 20, "shock_speed": 0.5, "manifold_points": 3}, "bodies": [])");
  const Scene scene = parse_recorded_scene(text, "recording.json");
  SolverSettings solver;
  solver.manifold_points = 3;
  expect_same_solver(scene.solver, solver);
  EXPECT_THROW(static_cast<void>(parse_scene(text, "scene.json")), Error);
  // Anything else wrong is still refused.
  EXPECT_THROW(static_cast<void>(parse_recorded_scene(
                   scene_text(R"("solver": {"velocity_iteration": 20}, "bodies": [])"), "r.json")),
               Error);
}

TEST(SceneFile, APairMaterialLeftPartlyOpenTakesTheMixOfItsBodies) {
  const Scene scene = parse_scene(scene_text(R"(
    "bodies": [{"friction": 0.2, "restitution": 0.1}, {"friction": 0.8, "restitution": 0.6}, {}],
    "pair_materials": [{"bodies": [0, 1]}, {"bodies": [2, 0], "friction": 0},
                       {"bodies": [1, 2], "restitution": 1}])"),
                                  "s.json");
  expect_same_pairs(scene.pair_materials,
                    {{.bodies = {0, 1}, .material = {mix_friction(0.2f, 0.8f), 0.6f}},
                     {.bodies = {2, 0}, .material = {0.0f, 0.3f}},
                     {.bodies = {1, 2}, .material = {mix_friction(0.8f, 0.5f), 1.0f}}});
}

TEST(SceneFile, BodyKeysOverrideTheDefaults) {
  const Scene scene = parse_scene(scene_text(R"(
    "defaults": {"triangles": 500, "size": 2, "mass": 3, "density": 10, "static": true,
                 "linear_velocity": [1, 0, 0],
                 "sphere_tree": {"method": "grid", "branching": 2, "depth": 4}},
    "bodies": [
      {},
      {"triangles": null, "size": null, "mass": null, "static": false,
       "sphere_tree": {"depth": 2}},
      {"density": 20, "linear_velocity": [0, 0, 1]}
    ])"),
                                  "s.json");
  ASSERT_EQ(scene.bodies.size(), 3U);
  const BodySpec& inherits = scene.bodies[0];
  EXPECT_EQ(inherits.triangles, std::optional<std::size_t>(500));
  EXPECT_EQ(inherits.size, std::optional<double>(2.0));
  EXPECT_EQ(inherits.mass, std::optional<double>(3.0));
  EXPECT_EQ(inherits.density, 10.0);
  EXPECT_TRUE(inherits.is_static);
  expect_same(inherits.linear_velocity, Vec3(1.0f, 0.0f, 0.0f), "linear_velocity");
  EXPECT_EQ(inherits.tree.method, BuildMethod::Grid);
  EXPECT_EQ(inherits.tree.branching, 2);
  EXPECT_EQ(inherits.tree.depth, 4);

  // null unsets; a sphere_tree object overrides only the keys it has.
  const BodySpec& unsets = scene.bodies[1];
  EXPECT_EQ(unsets.triangles, std::nullopt);
  EXPECT_EQ(unsets.size, std::nullopt);
  EXPECT_EQ(unsets.mass, std::nullopt);
  EXPECT_FALSE(unsets.is_static);
  EXPECT_EQ(unsets.tree.method, BuildMethod::Grid);
  EXPECT_EQ(unsets.tree.branching, 2);
  EXPECT_EQ(unsets.tree.depth, 2);

  const BodySpec& overrides = scene.bodies[2];
  EXPECT_EQ(overrides.density, 20.0);
  expect_same(overrides.linear_velocity, Vec3(0.0f, 0.0f, 1.0f), "linear_velocity");
  EXPECT_EQ(overrides.mass, std::optional<double>(3.0));
}

TEST_F(SceneFileOnDisk, SphereTreeFileReplacesTheBuildSettingsOfTheDefaults) {
  const Scene scene = parse_scene(scene_text(R"(
    "defaults": {"sphere_tree": {"method": "grid", "depth": 4}},
    "bodies": [{"sphere_tree": "trees/bunny.sph"}])"),
                                  scene_path());
  const TreeSpec& tree = scene.bodies.at(0).tree;
  EXPECT_EQ(tree.sph_file, std::optional<fs::path>("trees/bunny.sph"));
  EXPECT_EQ(tree.method, TreeSpec{}.method);
  EXPECT_EQ(tree.depth, TreeSpec{}.depth);
}

TEST(SceneFile, OrientationFormsGiveTheSameRotations) {
  const Scene scene = parse_scene(scene_text(R"("bodies": [
      {"orientation": {"yaw_degrees": 90}},
      {"orientation": {"axis": [0, 2, 0], "angle_degrees": 90}},
      {"orientation": {"w": 1, "x": 0, "y": 1, "z": 0}},
      {"orientation": {"axis": [1, 0, 0], "angle_degrees": -90}},
      {"orientation": {"w": 0, "x": 0, "y": 3, "z": 4}},
      {"orientation": {"w": 1, "x": 0, "y": 0, "z": 0}}
    ])"),
                                  "s.json");
  ASSERT_EQ(scene.bodies.size(), 6U);
  // Counter-clockwise about +y seen from above: +x turns to -z.
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE("body " + std::to_string(i));
    expect_rotation(scene.bodies[i].orientation, Vec3::UnitX(), -Vec3::UnitZ());
    EXPECT_NEAR(scene.bodies[i].orientation.norm(), 1.0f, 1e-7f);
  }
  expect_rotation(scene.bodies[3].orientation, Vec3::UnitY(), -Vec3::UnitZ());
  EXPECT_EQ(scene.bodies[4].orientation.coeffs(), Quat(0.0f, 0.0f, 0.6f, 0.8f).coeffs());
  EXPECT_EQ(scene.bodies[5].orientation.coeffs(), Quat::Identity().coeffs());
}

TEST(SceneFile, IntegralNumbersCountAsIntegers) {
  const Scene scene = parse_scene(R"({"format": "sphys-scene", "version": 1.0, "frames": 1e3,
      "bodies": [{"triangles": 4.0, "sphere_tree": {"depth": 2.0}}]})",
                                  "s.json");
  EXPECT_EQ(scene.frames, 1000);
  EXPECT_EQ(scene.bodies.at(0).triangles, std::optional<std::size_t>(4));
  EXPECT_EQ(scene.bodies.at(0).tree.depth, 2);
}

// A scene with every value drawn at random from its whole valid range.
class RandomScene {
 public:
  explicit RandomScene(std::uint32_t seed) : rng_(seed) {}

  Scene next() {
    Scene scene;
    scene.name = "s.json";
    scene.gravity = vec3_within(static_cast<float>(kMaxGravity));
    scene.time_step = in_range(1e-6, 1.0);
    scene.frames = std::uniform_int_distribution<int>(1, 10'000'000)(rng_);
    scene.paper_passes = std::uniform_int_distribution<int>(1, 1000)(rng_);
    scene.response = pick(std::array{ResponseMode::kPaper, ResponseMode::kPlausible});
    scene.collision_passes = std::uniform_int_distribution<int>(1, 64)(rng_);
    scene.max_collision_passes = std::uniform_int_distribution<int>(1, 64)(rng_);
    scene.collision_pass_travel = std::abs(any_float()) + 1e-30f;
    scene.solver = solver();
    scene.sleep = {
        .enabled = coin(), .speed = std::abs(any_float()), .time = std::abs(any_float())};
    scene.ground.kind = pick(std::array{GroundSpec::Kind::kNone, GroundSpec::Kind::kPlane,
                                        GroundSpec::Kind::kOctreeBox});
    scene.ground.height = within(1e5);
    scene.ground.size = in_range(1e-2, 1e5);
    scene.ground.thickness = in_range(1e-3, 1e4);
    scene.ground.depth = std::uniform_int_distribution<int>(1, 7)(rng_);
    scene.ground.restitution = unit_float();
    scene.ground.friction = std::abs(any_float());
    const int bodies = std::uniform_int_distribution<int>(0, 4)(rng_);
    for (int i = 0; i < bodies; ++i) scene.bodies.push_back(body());
    for (std::size_t i = 0; i + 1 < scene.bodies.size(); ++i) {
      if (!coin()) continue;
      PairMaterialSpec pair;
      pair.bodies =
          coin() ? std::array<std::size_t, 2>{i, i + 1} : std::array<std::size_t, 2>{i + 1, i};
      pair.material = {std::abs(any_float()), unit_float()};
      scene.pair_materials.push_back(pair);
    }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (coin()) scene.joints.push_back(joint(i, scene.bodies.size()));
    }
    return scene;
  }

 private:
  SolverSettings solver() {
    SolverSettings solver;
    solver.soft_substeps = std::uniform_int_distribution<std::uint32_t>(1, 64)(rng_);
    solver.contact_hertz = std::abs(any_float()) + 1.0f;
    solver.contact_damping_ratio = std::abs(any_float());
    solver.warm_starting = coin();
    solver.rolling_resistance = std::abs(any_float());
    solver.reuse_distance = std::abs(any_float());
    solver.restitution_threshold = std::abs(any_float());
    solver.linear_slop = std::abs(any_float());
    solver.max_correction_speed = std::abs(any_float());
    solver.contacts = pick(std::array{ContactSet::kAll, ContactSet::kReduced});
    solver.manifold_points = std::uniform_int_distribution<std::uint32_t>(1, 8)(rng_);
    solver.fast_pair_reach = std::abs(any_float());
    solver.contact_margin = std::abs(any_float());
    solver.speculative_contacts = coin();
    return solver;
  }

  BodySpec body() {
    BodySpec body;
    body.mesh = coin() ? "bunny" : "meshes/box.obj";
    if (coin()) body.triangles = std::uniform_int_distribution<std::size_t>(4, 4'294'967'295)(rng_);
    body.size = coin() ? std::optional<double>() : in_range(1e-3, 1e3);
    if (coin()) {
      body.tree.sph_file = "trees/bunny.sph";
    } else {
      body.tree.method =
          pick(std::array{BuildMethod::Octree, BuildMethod::Grid, BuildMethod::Spawn,
                          BuildMethod::Hubbard, BuildMethod::Merge, BuildMethod::Burst,
                          BuildMethod::Expand, BuildMethod::Combined, BuildMethod::Tight});
      body.tree.branching = std::uniform_int_distribution<int>(2, 8)(rng_);
      body.tree.depth = std::uniform_int_distribution<int>(1, 6)(rng_);
    }
    body.position = vec3_within(1e5f);
    Eigen::Vector4f wxyz;
    for (int k = 0; k < 4; ++k) wxyz[k] = std::normal_distribution<float>()(rng_);
    wxyz.normalize();
    body.orientation = Quat(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
    body.linear_velocity = vec3_within(1e4f);
    body.angular_velocity = vec3_within(1e4f);
    body.density = in_range(1e-3, 1e6);
    if (coin()) body.mass = in_range(1e-6, 1e9);
    body.restitution = unit_float();
    body.friction = std::abs(any_float());
    body.is_static = coin();
    return body;
  }

  // A joint of body `i` to another of the `bodies` or to the world, every field set.
  JointSpec joint(std::size_t i, std::size_t bodies) {
    JointSpec joint;
    joint.body_a = i;
    const std::size_t other = std::uniform_int_distribution<std::size_t>(0, bodies - 1)(rng_);
    if (other != i) joint.body_b = other;
    if (coin()) std::swap(joint.body_a, joint.body_b);
    JointDesc& d = joint.desc;
    d.type = pick(std::array{JointType::kHinge, JointType::kSlider, JointType::kBall,
                             JointType::kWeld, JointType::kDistance});
    d.anchor_a = vec3_within(1e5f);
    d.anchor_b = vec3_within(1e5f);
    d.axis_a = vec3_within(1e5f) + Vec3(1e-3f, 0.0f, 0.0f);
    d.axis_b = vec3_within(1e5f) + Vec3(0.0f, 0.0f, 1e-3f);
    const float low = within(1e5f);
    const float high = within(1e5f);
    d.limit = {.enabled = coin(), .lower = std::min(low, high), .upper = std::max(low, high)};
    if (!d.limit.enabled && coin()) std::swap(d.limit.lower, d.limit.upper);  // off: any bounds
    if (d.limit.enabled && d.type == JointType::kDistance) {
      d.limit.lower = std::abs(d.limit.lower);
      d.limit.upper = std::max(d.limit.lower, std::abs(d.limit.upper));
    }
    d.motor = {.enabled = coin(), .speed = within(1e4f), .max_effort = std::abs(any_float())};
    d.spring = {.enabled = coin(),
                .hertz = std::abs(any_float()),
                .damping_ratio = std::abs(any_float()),
                .target = within(1e5f)};
    d.cone = {.enabled = coin(), .angle = 3.0f * unit_float()};
    d.friction = std::abs(any_float());
    d.length = static_cast<float>(in_range(1e-5, 1e5));
    d.collide_connected = coin();
    return joint;
  }

  bool coin() { return std::uniform_int_distribution<int>(0, 1)(rng_) == 1; }
  template <typename T, std::size_t N>
  T pick(const std::array<T, N>& values) {
    return values[std::uniform_int_distribution<std::size_t>(0, N - 1)(rng_)];
  }
  // Any finite float, every exponent alike.
  float any_float() {
    for (;;) {
      const float value = std::bit_cast<float>(static_cast<std::uint32_t>(rng_()));
      if (std::isfinite(value)) return value;
    }
  }
  double any_double() {
    for (;;) {
      const double value = std::bit_cast<double>((std::uint64_t{rng_()} << 32) | rng_());
      if (std::isfinite(value)) return value;
    }
  }
  float unit_float() {
    for (;;) {
      const float value = std::abs(any_float());
      if (value <= 1.0f) return value;
    }
  }
  // Any double in [lo, hi] (0 < lo), every exponent between alike.
  double in_range(double lo, double hi) {
    const double u = std::uniform_real_distribution<double>()(rng_);
    return std::clamp(lo * std::pow(hi / lo, u), lo, hi);
  }
  // Any finite double, or float, of magnitude at most `limit`, every exponent alike.
  double within(double limit) {
    for (;;) {
      const double value = any_double();
      if (std::abs(value) <= limit) return value;
    }
  }
  float within(float limit) {
    for (;;) {
      const float value = any_float();
      if (std::abs(value) <= limit) return value;
    }
  }
  Vec3 vec3_within(float limit) { return {within(limit), within(limit), within(limit)}; }

  std::mt19937 rng_;
};

TEST_F(SceneFileOnDisk, RandomScenesRoundTripBitForBit) {
  RandomScene scenes(20240611);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    Scene scene = scenes.next();
    scene.name = "scene.json";
    scene.base_directory = dir_.path();
    const std::string text = scene_to_json(scene);
    const Scene back = parse_scene(text, scene_path());
    expect_same_scene(back, scene);
    EXPECT_EQ(scene_to_json(back), text);
  }
}

TEST_F(SceneFileOnDisk, FullSceneRoundTripsBitForBit) {
  const Scene scene = parse_scene(kFullScene, scene_path());
  expect_same_scene(parse_scene(scene_to_json(scene), scene_path()), scene);
}

TEST(SceneFile, EachJointTypeRoundTripsBitForBit) {
  const Scene scene = parse_scene(scene_text(R"("bodies": [{}, {}, {}],
    "joints": [
      {"type": "hinge", "body_a": null, "body_b": 0, "anchor_a": [0, 2, 0], "anchor_b": [0, 0.5, 0],
       "axis_a": [0, 0, 1], "axis_b": [0, 0, 1], "limit": {"lower": -1.2, "upper": 0.3},
       "motor": {"speed": 1.5, "max_effort": 20}},
      {"type": "slider", "body_a": 0, "body_b": 1, "axis_a": [1, 0, 0],
       "spring": {"hertz": 2, "damping_ratio": 0.1, "target": 0.2}},
      {"type": "ball", "body_a": 1, "body_b": 2, "anchor_b": [0.1, 0, 0],
       "cone": {"angle": 0.3}, "limit": {"lower": -0.2, "upper": 0.2}},
      {"type": "weld", "body_a": 2, "body_b": null, "spring": {"hertz": 10, "damping_ratio": 1},
       "collide_connected": true},
      {"type": "distance", "body_a": 0, "body_b": 2, "length": 1.75,
       "limit": {"enabled": false, "lower": 3, "upper": 0.5}}
    ])"),
                                  "s.json");
  ASSERT_EQ(scene.joints.size(), 5U);
  const std::array types = {JointType::kHinge, JointType::kSlider, JointType::kBall,
                            JointType::kWeld, JointType::kDistance};
  for (std::size_t k = 0; k < types.size(); ++k) EXPECT_EQ(scene.joints[k].desc.type, types[k]);
  EXPECT_EQ(scene.joints[0].body_a, std::nullopt);
  EXPECT_EQ(scene.joints[0].body_b, std::optional<std::size_t>(0));
  EXPECT_TRUE(scene.joints[0].desc.limit.enabled);
  EXPECT_EQ(scene.joints[0].desc.limit.lower, -1.2f);
  EXPECT_TRUE(scene.joints[0].desc.motor.enabled);
  EXPECT_EQ(scene.joints[0].desc.motor.max_effort, 20.0f);
  EXPECT_FALSE(scene.joints[0].desc.spring.enabled);
  EXPECT_EQ(scene.joints[2].desc.cone.angle, 0.3f);
  EXPECT_EQ(scene.joints[3].body_b, std::nullopt);
  EXPECT_TRUE(scene.joints[3].desc.collide_connected);
  EXPECT_EQ(scene.joints[4].desc.length, 1.75f);
  EXPECT_FALSE(scene.joints[4].desc.limit.enabled);
  // A limit that is off is kept as written, unchecked, as the world keeps it.
  EXPECT_EQ(scene.joints[4].desc.limit.lower, 3.0f);
  const std::string text = scene_to_json(scene);
  const Scene back = parse_scene(text, "s.json");
  expect_same_scene(back, scene);
  EXPECT_EQ(scene_to_json(back), text);
}

TEST(SceneFile, WrittenFloatsUseTheirShortestForm) {
  Scene scene;
  scene.bodies.emplace_back();
  scene.bodies[0].restitution = 0.3f;
  // 7.038531e-26 is the one float magnitude whose shortest form, read as a double, rounds to a
  // neighbouring float: it must still come back exactly.
  const float tricky = std::bit_cast<float>(std::uint32_t{0x15ae43fd});
  scene.bodies[0].position = Vec3(0.1f, -tricky, tricky);
  scene.gravity = Vec3(0.0f, -9.81f, 0.0f);
  const std::string text = scene_to_json(scene);
  EXPECT_THAT(text, HasSubstr("\"restitution\": 0.3,"));
  EXPECT_THAT(text, HasSubstr("-9.81"));
  EXPECT_THAT(text, HasSubstr("\n  \"version\": 1,\n"));
  const Scene back = parse_scene(text, "s.json");
  expect_same(back.bodies.at(0).position, scene.bodies[0].position, "position");
  expect_same(back.gravity, scene.gravity, "gravity");
}

struct BadCase {
  std::string text;
  std::string path;  // JSON pointer the message must name
  std::string reason;
};

TEST(SceneFile, BadValuesNameTheirPathAndReason) {
  const std::vector<BadCase> cases = {
      // Unknown keys, with a suggestion when one is close.
      {scene_text(R"("gravty": [0, 0, 0], "bodies": [])"), "/gravty",
       "unknown key; did you mean \"gravity\"?"},
      {scene_text(R"("bodies": [{"colour": "red"}])"), "/bodies/0/colour",
       "unknown key (valid: mesh, triangles, size, sphere_tree, position, orientation"},
      {scene_text(R"("bodies": [{}, {"densty": 3}])"), "/bodies/1/densty",
       "did you mean \"density\"?"},
      {scene_text(R"("ground": {"kind": "plane"}, "bodies": [])"), "/ground/kind", "unknown key"},
      {scene_text(R"("bodies": [{"sphere_tree": {"levels": 3}}])"), "/bodies/0/sphere_tree/levels",
       "unknown key"},
      {scene_text(R"("bodies": [{"orientation": {"yaw": 3}}])"), "/bodies/0/orientation/yaw",
       "did you mean \"yaw_degrees\"?"},
      {scene_text(R"("bodies": [{"angularVelocity": [0, 0, 0]}])"), "/bodies/0/angularVelocity",
       "did you mean \"angular_velocity\"?"},
      {scene_text(R"("bodies": [{"q": {}}])"), "/bodies/0/q", "unknown key (valid: "},
      {scene_text(R"("bodies": [], "a/b~c": 1)"), "/a~1b~0c", "unknown key"},
      {scene_text(R"("defaults": {"position": [0, 0, 0]}, "bodies": [])"), "/defaults/position",
       "set per body, not in \"defaults\""},
      // Wrong types.
      {scene_text(R"("time_step": "fast", "bodies": [])"), "/time_step",
       "expected a number, got a string \"fast\""},
      {scene_text(R"("bodies": [{"static": 1}])"), "/bodies/0/static",
       "expected true or false, got a number 1"},
      {scene_text(R"("gravity": [0, -9.81], "bodies": [])"), "/gravity",
       "expected 3 numbers [x, y, z], got 2"},
      {scene_text(R"("gravity": [0, null, 0], "bodies": [])"), "/gravity/1",
       "expected a number, got null"},
      {scene_text(R"("gravity": {"x": 0}, "bodies": [])"), "/gravity",
       "expected an array of 3 numbers, got an object {\"x\":0}"},
      {scene_text(R"("bodies": {})"), "/bodies", "expected an array of bodies, got an object"},
      {scene_text(R"("bodies": [3])"), "/bodies/0", "expected an object, got a number 3"},
      {scene_text(R"("bodies": [{"mesh": 7}])"), "/bodies/0/mesh", "expected a string"},
      {scene_text(R"("bodies": [{"sphere_tree": 3}])"), "/bodies/0/sphere_tree",
       "expected an object {\"method\", \"branching\", \"depth\"} or the path of a .sph file"},
      {scene_text(R"("ground": [], "bodies": [])"), "/ground", "expected an object, got an array"},
      {scene_text(R"("bodies": [{"mesh": "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx"}])"),
       "/bodies/0/mesh", "no such file"},
      // Numbers out of range.
      {scene_text(R"("bodies": [{}, {}, {}, {"density": -2}])"), "/bodies/3/density",
       "must be positive, got -2"},
      {scene_text(R"("bodies": [{"density": 0}])"), "/bodies/0/density", "must be positive, got 0"},
      {scene_text(R"("bodies": [{"mass": 0}])"), "/bodies/0/mass", "must be positive, got 0"},
      {scene_text(R"("bodies": [{"mass": -12.5}])"), "/bodies/0/mass",
       "must be positive, got -12.5"},
      {scene_text(R"("defaults": {"mass": -1}, "bodies": [])"), "/defaults/mass",
       "must be positive, got -1"},
      {scene_text(R"("time_step": 0, "bodies": [])"), "/time_step", "must be positive, got 0"},
      {scene_text(R"("time_step": -0.01, "bodies": [])"), "/time_step",
       "must be positive, got -0.01"},
      {scene_text(R"("time_step": 2, "bodies": [])"), "/time_step",
       "must be between 1e-06 and 1 s, got 2"},
      // Figures that would overflow or vanish in the simulation's products are refused here,
      // named, rather than failing later: each just past its limit.
      {scene_text(R"("gravity": [0, -3e38, 0], "bodies": [])"), "/gravity/1",
       "must be between -1000 and 1000, got -3e+38"},
      {scene_text(R"("gravity": [1000.5, 0, 0], "bodies": [])"), "/gravity/0",
       "must be between -1000 and 1000, got 1000.5"},
      {scene_text(R"("time_step": 1e-320, "bodies": [])"), "/time_step",
       "must be between 1e-06 and 1 s, got 1e-320"},
      {scene_text(R"("bodies": [{"density": 3.4e38}])"), "/bodies/0/density",
       "must be between 0.001 and 1e+06 kg/m³, got 3.4e+38"},
      {scene_text(R"("bodies": [{"density": 0.0009}])"), "/bodies/0/density",
       "must be between 0.001 and 1e+06 kg/m³, got 0.0009"},
      {scene_text(R"("bodies": [{"mass": 1e-300}])"), "/bodies/0/mass",
       "must be between 1e-06 and 1e+09 kg, got 1e-300"},
      {scene_text(R"("bodies": [{"mass": 1.1e9}])"), "/bodies/0/mass",
       "must be between 1e-06 and 1e+09 kg, got 1100000000.0"},
      {scene_text(R"("defaults": {"size": 9.2e18}, "bodies": [])"), "/defaults/size",
       "must be between 0.001 and 1000 m, got 9.2e+18"},
      {scene_text(R"("bodies": [{"size": 0.0009}])"), "/bodies/0/size",
       "must be between 0.001 and 1000 m, got 0.0009"},
      {scene_text(R"("bodies": [{"position": [0, 100001, 0]}])"), "/bodies/0/position/1",
       "must be between -1e+05 and 1e+05 m, got 100001"},
      {scene_text(R"("bodies": [{"linear_velocity": [-10001, 0, 0]}])"),
       "/bodies/0/linear_velocity/0", "must be between -10000 and 10000 m/s, got -10001"},
      {scene_text(R"("bodies": [{"angular_velocity": [0, 0, 20000]}])"),
       "/bodies/0/angular_velocity/2", "must be between -10000 and 10000 rad/s, got 20000"},
      {scene_text(R"("ground": {"thickness": 3.4e38}, "bodies": [])"), "/ground/thickness",
       "must be between 0.001 and 10000 m, got 3.4e+38"},
      {scene_text(R"("ground": {"size": 0.001}, "bodies": [])"), "/ground/size",
       "must be between 0.01 and 1e+05 m, got 0.001"},
      {scene_text(R"("ground": {"height": -2e5}, "bodies": [])"), "/ground/height",
       "must be between -1e+05 and 1e+05 m, got -200000"},
      {scene_text(R"("frames": 2.5, "bodies": [])"), "/frames", "must be an integer, got 2.5"},
      {scene_text(R"("paper_passes": 0, "bodies": [])"), "/paper_passes",
       "must be between 1 and 1000, got 0"},
      {scene_text(R"("frames": 0, "bodies": [])"), "/frames",
       "must be between 1 and 10000000, got 0"},
      {scene_text(R"("frames": 99999999999999999999, "bodies": [])"), "/frames",
       "must be between 1 and 10000000, got 1e+20"},
      {scene_text(R"("bodies": [{"triangles": 3}])"), "/bodies/0/triangles",
       "must be 0 (keep every triangle) or at least 4, got 3"},
      {scene_text(R"("bodies": [{"triangles": -1}])"), "/bodies/0/triangles",
       "must be between 0 and 4294967295, got -1"},
      {scene_text(R"("bodies": [{"size": 0}])"), "/bodies/0/size", "must be positive, got 0"},
      {scene_text(R"("bodies": [{"restitution": 1.5}])"), "/bodies/0/restitution",
       "must be between 0 and 1, got 1.5"},
      {scene_text(R"("bodies": [{"friction": -0.5}])"), "/bodies/0/friction",
       "must not be negative, got -0.5"},
      {scene_text(R"("bodies": [{"friction": 1e39}])"), "/bodies/0/friction",
       "does not fit in single precision, got 1e+39"},
      {scene_text(R"("bodies": [{"position": [0, -4e38, 0]}])"), "/bodies/0/position/1",
       "does not fit in single precision"},
      {scene_text(R"("bodies": [{"sphere_tree": {"branching": 9}}])"),
       "/bodies/0/sphere_tree/branching", "must be between 2 and 8, got 9"},
      {scene_text(R"("bodies": [{"sphere_tree": {"depth": 7}}])"), "/bodies/0/sphere_tree/depth",
       "must be between 1 and 6, got 7"},
      {scene_text(R"("ground": {"depth": 0}, "bodies": [])"), "/ground/depth",
       "must be between 1 and 7, got 0"},
      {scene_text(R"("ground": {"size": -16}, "bodies": [])"), "/ground/size",
       "must be positive, got -16"},
      {scene_text(R"("ground": {"thickness": 0}, "bodies": [])"), "/ground/thickness",
       "must be positive, got 0"},
      // Enumerations list their values.
      {scene_text(R"("response": "bogus", "bodies": [])"), "/response",
       "unknown value \"bogus\" (valid: \"paper\", \"plausible\")"},
      {scene_text(R"("contacts": "some", "bodies": [])"), "/contacts",
       "unknown value \"some\" (valid: \"all\", \"reduced\")"},
      {scene_text(R"("ground": {"type": "box"}, "bodies": [])"), "/ground/type",
       "unknown value \"box\" (valid: \"octree-box\", \"plane\", \"none\")"},
      {scene_text(R"("bodies": [{"sphere_tree": {"method": "best"}}])"),
       "/bodies/0/sphere_tree/method", "unknown sphere-tree method 'best' (valid: octree, grid"},
      // Orientations.
      {scene_text(R"("bodies": [{"orientation": {"w": 0, "x": 0, "y": 0, "z": 0}}])"),
       "/bodies/0/orientation", "a zero-length quaternion is no rotation"},
      {scene_text(R"("bodies": [{"orientation": {"axis": [0, 0, 0], "angle_degrees": 5}}])"),
       "/bodies/0/orientation/axis", "a zero-length axis has no direction"},
      {scene_text(R"("bodies": [{"orientation": {"axis": [0, 1, 0]}}])"),
       "/bodies/0/orientation/angle_degrees", "missing; an axis needs an angle"},
      {scene_text(R"("bodies": [{"orientation": {"w": 1, "x": 0, "z": 0}}])"),
       "/bodies/0/orientation/y", "missing; a quaternion needs w, x, y and z"},
      {scene_text(R"("bodies": [{"orientation": {"w": 1, "yaw_degrees": 5}}])"),
       "/bodies/0/orientation", "mixes forms; give one of"},
      {scene_text(R"("bodies": [{"orientation": {}}])"), "/bodies/0/orientation",
       "expected one of {\"w\", \"x\", \"y\", \"z\"}, {\"yaw_degrees\"} or {\"axis\", "
       "\"angle_degrees\"}"},
      // The header and the required keys.
      {R"({"version": 1, "bodies": []})", "/format",
       "missing; a scene file starts with \"format\": \"sphys-scene\""},
      {R"({"format": "sphys-recording", "version": 1, "bodies": []})", "/format",
       "expected \"sphys-scene\", got a string \"sphys-recording\""},
      {R"({"format": "sphys-scene", "bodies": []})", "/version", "missing"},
      {R"({"format": "sphys-scene", "version": 2, "bodies": []})", "/version",
       "unsupported version 2; this build reads version 1"},
      {R"({"format": "sphys-scene", "version": "1", "bodies": []})", "/version",
       "expected a number, got a string \"1\""},
      {scene_text(R"("frames": 10)"), "/bodies", "missing"},
      // The world's settings.
      {scene_text(R"("collision_passes": 0, "bodies": [])"), "/collision_passes",
       "must be between 1 and 64, got 0"},
      {scene_text(R"("collision_passes": 65, "bodies": [])"), "/collision_passes",
       "must be between 1 and 64, got 65"},
      {scene_text(R"("collision_passes": 1.5, "bodies": [])"), "/collision_passes",
       "must be an integer, got 1.5"},
      {scene_text(R"("solver": [], "bodies": [])"), "/solver", "expected an object, got an array"},
      {scene_text(R"("solver": {"soft_substep": 3}, "bodies": [])"), "/solver/soft_substep",
       "unknown key; did you mean \"soft_substeps\"?"},
      {scene_text(R"("solver": {"soft_substeps": 0}, "bodies": [])"), "/solver/soft_substeps",
       "must be between 1 and 64, got 0"},
      // Renamed settings are refused naming the new name.
      {scene_text(R"("substeps": 2, "bodies": [])"), "/substeps",
       "substeps was removed: renamed collision_passes"},
      {scene_text(R"("max_substeps": 2, "bodies": [])"), "/max_substeps",
       "max_substeps was removed: renamed max_collision_passes"},
      // The sequential-impulse solver's settings, removed with it, are refused by name.
      {scene_text(R"("solver": {"velocity_iterations": 20}, "bodies": [])"),
       "/solver/velocity_iterations",
       "solver.velocity_iterations was removed: the soft step solves and relaxes each contact "
       "once per substep; set solver.soft_substeps"},
      {scene_text(R"("solver": {"method": "soft_step"}, "bodies": [])"), "/solver/method",
       "solver.method was removed: the soft step is the only solver; delete the setting"},
      {scene_text(R"("solver": {"position_correction": 0.2}, "bodies": [])"),
       "/solver/position_correction",
       "solver.position_correction was removed: the soft step's contact springs push bodies "
       "apart; set solver.contact_hertz and solver.contact_damping_ratio"},
      {scene_text(R"("solver": {"warm_starting": "yes"}, "bodies": [])"), "/solver/warm_starting",
       "expected true or false, got a string \"yes\""},
      {scene_text(R"("solver": {"contact_hertz": 0}, "bodies": [])"), "/solver/contact_hertz",
       "must be positive, got 0"},
      {scene_text(R"("solver": {"rolling_resistance": "none"}, "bodies": [])"),
       "/solver/rolling_resistance", "expected a number, got a string \"none\""},
      {scene_text(R"("max_collision_passes": 0, "bodies": [])"), "/max_collision_passes",
       "must be between 1 and 64, got 0"},
      {scene_text(R"("collision_pass_travel": 0, "bodies": [])"), "/collision_pass_travel",
       "must be positive, got 0"},
      {scene_text(R"("solver": {"restitution_threshold": -1}, "bodies": [])"),
       "/solver/restitution_threshold", "must not be negative, got -1"},
      {scene_text(R"("solver": {"linear_slop": -0.01}, "bodies": [])"), "/solver/linear_slop",
       "must not be negative, got -0.01"},
      {scene_text(R"("solver": {"max_correction_speed": 1e39}, "bodies": [])"),
       "/solver/max_correction_speed", "does not fit in single precision, got 1e+39"},
      {scene_text(R"("solver": {"manifold_points": 9}, "bodies": [])"), "/solver/manifold_points",
       "must be between 1 and 8, got 9"},
      {scene_text(R"("solver": {"contact_margin": "wide"}, "bodies": [])"),
       "/solver/contact_margin", "expected a number, got a string \"wide\""},
      {scene_text(R"("solver": {"speculative_contacts": 1}, "bodies": [])"),
       "/solver/speculative_contacts", "expected true or false, got a number 1"},
      {scene_text(R"("sleep": {"enable": false}, "bodies": [])"), "/sleep/enable",
       "unknown key; did you mean \"enabled\"?"},
      {scene_text(R"("sleep": {"speed": -0.05}, "bodies": [])"), "/sleep/speed",
       "must not be negative, got -0.05"},
      {scene_text(R"("sleep": {"time": null}, "bodies": [])"), "/sleep/time",
       "expected a number, got null"},
      // Pair materials.
      {scene_text(R"("bodies": [], "pair_materials": {})"), "/pair_materials",
       "expected an array of pair materials, got an object"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"friction": 1}])"),
       "/pair_materials/0/bodies", "missing; a pair material names its two bodies"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1], "frction": 1}])"),
       "/pair_materials/0/frction", "unknown key; did you mean \"friction\"?"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1, 1]}])"),
       "/pair_materials/0/bodies", "expected 2 body indices [i, j], got 3"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": 1}])"),
       "/pair_materials/0/bodies", "expected an array of 2 body indices [i, j], got a number 1"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 2]}])"),
       "/pair_materials/0/bodies/1", "no body 2; /bodies has 2 (indices from 0)"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [-1, 0]}])"),
       "/pair_materials/0/bodies/0", "must be between 0 and 9007199254740992, got -1"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0.5, 1]}])"),
       "/pair_materials/0/bodies/0", "must be an integer, got 0.5"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [1, 1]}])"),
       "/pair_materials/0/bodies", "a pair needs two different bodies, got [1,1]"},
      {scene_text(R"("bodies": [{}, {}, {}],
          "pair_materials": [{"bodies": [0, 1]}, {"bodies": [1, 2]}, {"bodies": [1, 0]}])"),
       "/pair_materials/2/bodies", "this pair already has a material, at /pair_materials/0"},
      {scene_text(R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1], "friction": -1}])"),
       "/pair_materials/0/friction", "must not be negative, got -1"},
      {scene_text(
           R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1], "restitution": 1.5}])"),
       "/pair_materials/0/restitution", "must be between 0 and 1, got 1.5"},
      {scene_text(
           R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1], "restitution": -0.1}])"),
       "/pair_materials/0/restitution", "must be between 0 and 1, got -0.1"},
      // Duplicate keys would otherwise be resolved silently.
      {scene_text(R"("bodies": [{"density": 1, "density": 2}])"), "/bodies/0/density",
       "duplicate key"},
  };
  for (const BadCase& bad : cases) {
    SCOPED_TRACE(bad.text);
    EXPECT_THAT(parse_error(bad.text),
                AllOf(StartsWith("scene.json: " + bad.path + ": "), HasSubstr(bad.reason)));
  }
}

TEST(SceneFile, BadJointsNameTheirPathAndReason) {
  const auto joints = [](std::string_view entries) {
    return scene_text(R"("bodies": [{}, {}, {}, {}, {}], "joints": [)" + std::string(entries) +
                      "]");
  };
  constexpr std::string_view kHinge = R"({"type": "hinge", "body_a": 0, "body_b": 1})";
  const std::string hinges = std::string(kHinge) + ", " + std::string(kHinge) + ", ";
  const std::vector<BadCase> cases = {
      {scene_text(R"("bodies": [], "joints": {})"), "/joints", "expected an array of joints"},
      {joints(hinges + R"({"type": "hinge", "body_a": 0, "body_b": 7})"), "/joints/2/body_b",
       "no body 7; /bodies has 5 (indices from 0)"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "limit": {"lower": 1, "upper": 0}})"),
       "/joints/0/limit", "lower 1 > upper 0"},
      {joints(R"({"type": "hnge", "body_a": 0, "body_b": 1})"), "/joints/0/type", "hinge"},
      {joints(R"({"body_a": 0, "body_b": 1})"), "/joints/0/type",
       "missing; a joint names its type"},
      {joints(R"({"type": "ball", "body_a": 0})"), "/joints/0/body_b",
       "missing; a joint names its two bodies (null for the world)"},
      {joints(R"({"type": "ball", "body_a": null, "body_b": null})"), "/joints/0/body_b",
       "a joint needs a body; both are the world"},
      {joints(R"({"type": "ball", "body_a": 3, "body_b": 3})"), "/joints/0/body_b",
       "the same body as body_a (3)"},
      {joints(R"({"type": "ball", "body_a": -1, "body_b": 3})"), "/joints/0/body_a",
       "must be between 0 and"},
      {joints(R"({"type": "ball", "body_a": 0, "body_b": 1, "ancor_a": [0, 0, 0]})"),
       "/joints/0/ancor_a", "unknown key; did you mean \"anchor_a\"?"},
      {joints(R"({"type": "ball", "body_a": 0, "body_b": 1, "anchor_b": [0, 2e5, 0]})"),
       "/joints/0/anchor_b/1", "must be between -1e+05 and 1e+05 m, got 200000"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "axis_a": [0, 0, 0]})"),
       "/joints/0/axis_a", "a zero-length axis has no direction"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "axis_b": [0, 1]})"),
       "/joints/0/axis_b", "3"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "limit": {"lowr": 1}})"),
       "/joints/0/limit/lowr", "unknown key; did you mean \"lower\"?"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "limit": {"enabled": 1}})"),
       "/joints/0/limit/enabled", "expected true or false"},
      {joints(R"({"type": "distance", "body_a": 0, "body_b": 1, "limit": {"lower": -1}})"),
       "/joints/0/limit/lower", "a distance joint's shortest length must not be negative, got -1"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "limit": {"upper": -0.5}})"),
       "/joints/0/limit", "lower 0 > upper -0.5"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "motor": {"max_effort": -5}})"),
       "/joints/0/motor/max_effort", "must not be negative, got -5"},
      {joints(R"({"type": "ball", "body_a": 0, "body_b": 1, "friction": -0.5})"),
       "/joints/0/friction", "must not be negative, got -0.5"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "motor": {"speed": 1e5}})"),
       "/joints/0/motor/speed", "must be between -10000 and 10000 rad/s or m/s, got 100000"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "spring": {"hertz": -1}})"),
       "/joints/0/spring/hertz", "must not be negative, got -1"},
      {joints(R"({"type": "hinge", "body_a": 0, "body_b": 1, "spring": {"damping_ratio": -2}})"),
       "/joints/0/spring/damping_ratio", "must not be negative, got -2"},
      {joints(R"({"type": "ball", "body_a": 0, "body_b": 1, "cone": {"angle": 4}})"),
       "/joints/0/cone/angle", "must be between 0 and 3.14159"},
      {joints(R"({"type": "ball", "body_a": 0, "body_b": 1, "cone": 0.5})"), "/joints/0/cone",
       "expected an object"},
      {joints(R"({"type": "distance", "body_a": 0, "body_b": 1, "length": 0})"), "/joints/0/length",
       "must be positive, got 0"},
      {joints(R"({"type": "distance", "body_a": 0, "body_b": 1, "length": 2e5})"),
       "/joints/0/length", "must be between 1e-06 and 1e+05 m, got 200000"},
      {joints(R"({"type": "weld", "body_a": 0, "body_b": 1, "collide_connected": "yes"})"),
       "/joints/0/collide_connected", "expected true or false"},
  };
  for (const BadCase& bad : cases) {
    SCOPED_TRACE(bad.text);
    EXPECT_THAT(parse_error(bad.text),
                AllOf(StartsWith("scene.json: " + bad.path + ": "), HasSubstr(bad.reason)));
  }
}

TEST(SceneFile, NonFiniteNumbersAreNamedWithLineAndColumn) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"NaN", "scene.json:3: column 16: NaN is not a number in JSON; every number must be finite"},
      {"Infinity", "scene.json:3: column 16: Infinity is not a number in JSON"},
      {"-Infinity", "scene.json:3: column 16: -Infinity is not a number in JSON"},
      {"nan", "scene.json:3: column 16: nan is not a number in JSON"},
      {"1e400", "scene.json:3: column 16: the number 1e400 is beyond the range of a double"},
      {"-1e400", "scene.json:3: column 16: the number -1e400 is beyond the range of a double"},
  };
  for (const auto& [value, message] : cases) {
    const std::string text = std::string("{\n  ") + std::string(kHeader) +
                             ",\n  \"time_step\": " + value + ",\n  \"bodies\": []\n}\n";
    EXPECT_THAT(parse_error(text), StartsWith(message)) << text;
  }
}

TEST(SceneFile, NonFiniteNumbersAreRefusedAtAnyDepth) {
  const std::string text = std::string("{\n  ") + std::string(kHeader) +
                           ",\n  \"solver\": {\"linear_slop\": NaN},\n  \"bodies\": []\n}\n";
  EXPECT_THAT(parse_error(text),
              StartsWith("scene.json:3: column 29: NaN is not a number in JSON"));
}

TEST(SceneFile, TextThatIsNotJsonNamesLineAndColumn) {
  EXPECT_THAT(parse_error("{\n  \"bodies\": [\n    {\"mesh\": 'bunny'}\n  ]\n}"),
              StartsWith("scene.json:3: column 14: not valid JSON: syntax error"));
  EXPECT_THAT(parse_error(""), StartsWith("scene.json:1: column 1: not valid JSON: "));
  EXPECT_THAT(parse_error(scene_text(R"("bodies": [])") + " x"),
              HasSubstr("expected end of input"));
  EXPECT_THAT(parse_error("[1, 2]"),
              Eq("scene.json: expected a JSON object at the top level, got an array [1,2]"));
}

// Each open array or object keeps its JSON pointer: unbounded, 10^5 unclosed '[' took 9.8 GB.
TEST(SceneFile, NestingIsBoundedAsContainersOpen) {
  EXPECT_EQ(parse_error(std::string(100'000, '[')),
            "scene.json: /0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0: arrays and objects nested more than "
            "16 deep");
  // 16 deep is still read (and refused for what it is).
  EXPECT_THAT(parse_error(std::string(16, '[') + std::string(16, ']')),
              StartsWith("scene.json: expected a JSON object at the top level"));
}

// "{}," is a body: a 30 MB file of 10^7 of them took 4.2 GB and minutes before this bound. The
// millionth body is read, the next is refused as it opens, before the rest of the file is parsed.
std::string bodies_text(std::size_t count, std::string_view tail) {
  std::string text = R"({"format": "sphys-scene", "version": 1, "bodies": [)";
  for (std::size_t i = 0; i < count; ++i) text += i == 0 ? "{}" : ",{}";
  return text + std::string(tail);
}

TEST(SceneFile, BodiesAreBoundedAsTheyAreRead) {
  EXPECT_EQ(parse_error(bodies_text(kMaxSceneBodies + 1, "")),
            "scene.json: /bodies: more than 1000000 bodies; a scene holds at most that many");
  EXPECT_EQ(parse_scene(bodies_text(kMaxSceneBodies, "]}"), "scene.json").bodies.size(),
            kMaxSceneBodies);
}

TEST_F(SceneFileOnDisk, RelativePathsResolveAgainstTheScenesFolder) {
  const std::string text =
      scene_text(R"("bodies": [{"mesh": "meshes/box.obj", "sphere_tree": "trees/bunny.sph"}])");
  const Scene scene = read_scene_file(dir_.write("scene.json", text));
  EXPECT_EQ(scene.bodies.at(0).mesh, "meshes/box.obj");
  // The same text elsewhere finds neither file.
  const fs::path elsewhere = dir_.path() / "trees" / "scene.json";
  EXPECT_THAT(parse_error(text, elsewhere),
              AllOf(StartsWith(elsewhere.string() + ": /bodies/0/mesh: no such file: "),
                    HasSubstr((dir_.path() / "trees" / "meshes/box.obj").string())));
  // An absolute path needs no folder.
  const std::string absolute =
      scene_text(R"("bodies": [{"mesh": ")" + (dir_.path() / "meshes/box.obj").string() + "\"}]");
  EXPECT_EQ(parse_scene(absolute, elsewhere).bodies.at(0).mesh,
            (dir_.path() / "meshes/box.obj").string());
}

TEST_F(SceneFileOnDisk, MissingMeshAndTreeFilesAreNamed) {
  EXPECT_EQ(parse_error(scene_text(R"("bodies": [{"mesh": "meshes/gone.obj"}])"), scene_path()),
            scene_path().string() +
                ": /bodies/0/mesh: no such file: " + (dir_.path() / "meshes/gone.obj").string());
  EXPECT_THAT(parse_error(scene_text(R"("defaults": {"sphere_tree": "gone.sph"}, "bodies": [])"),
                          scene_path()),
              HasSubstr(": /defaults/sphere_tree: no such file: "));
  EXPECT_THAT(parse_error(scene_text(R"("bodies": [{"mesh": "meshes"}])"), scene_path()),
              HasSubstr(": /bodies/0/mesh: is a directory, not a mesh file: "));
  EXPECT_THAT(parse_error(scene_text(R"("bodies": [{"sphere_tree": ""}])"), scene_path()),
              HasSubstr(": /bodies/0/sphere_tree: expected the path of a .sph file, got \"\""));
}

TEST_F(SceneFileOnDisk, UnreadableFilesAreNamed) {
  EXPECT_EQ(read_error(dir_.path() / "none.json"),
            (dir_.path() / "none.json").string() + ": no such file");
  EXPECT_EQ(read_error(dir_.path() / "meshes"),
            (dir_.path() / "meshes").string() + ": is a directory, not a scene file");
  const std::string full(kFullScene);
  const fs::path truncated = dir_.write("truncated.json", full.substr(0, full.find("\"frames\"")));
  EXPECT_THAT(read_error(truncated),
              AllOf(StartsWith(truncated.string() + ":6: column 2: "),
                    HasSubstr("not valid JSON: "), HasSubstr("unexpected end of input")));
}

// The keys a schema object lists under "properties".
std::set<std::string> property_names(const nlohmann::json& schema) {
  std::set<std::string> names;
  for (const auto& item : schema.at("properties").items()) names.insert(item.key());
  return names;
}

std::set<std::string> object_keys(const nlohmann::json& object) {
  std::set<std::string> keys;
  for (const auto& item : object.items()) keys.insert(item.key());
  return keys;
}

std::string read_doc(std::string_view name) {
  const fs::path path = fs::path(__FILE__).parent_path() / "../../../docs" / name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot open " << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json read_schema() { return nlohmann::json::parse(read_doc("scene.schema.json")); }

TEST(SceneFileDocs, TheExampleReadsAsDescribed) {
  const std::string doc = read_doc("scenes.md");
  const std::string fence = "```json\n";
  const std::size_t begin = doc.find(fence);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = doc.find("```", begin + fence.size());
  ASSERT_NE(end, std::string::npos);
  const Scene scene =
      parse_scene(doc.substr(begin + fence.size(), end - begin - fence.size()), "example.json");
  ASSERT_EQ(scene.bodies.size(), 3U);
  EXPECT_EQ(scene.frames, 880);
  EXPECT_EQ(scene.ground.kind, GroundSpec::Kind::kOctreeBox);
  const BodySpec& last = scene.bodies[2];
  EXPECT_EQ(last.mesh, "bunny");
  EXPECT_EQ(last.triangles, std::optional<std::size_t>(2000));
  EXPECT_EQ(last.mass, std::optional<double>(12.5));
  EXPECT_EQ(last.tree.method, BuildMethod::Combined);
  EXPECT_EQ(last.tree.depth, 2);
  // 45 degrees about (1, 0, 1): the axis stays put, +y turns towards (-1, 0, 1)/2 + y/sqrt(2).
  const float half = std::sqrt(0.5f);
  expect_rotation(last.orientation, Vec3(half, 0.0f, half), Vec3(half, 0.0f, half));
  expect_rotation(last.orientation, Vec3::UnitY(), Vec3(-0.5f, half, 0.5f));
  // The second and third bunnies grip harder; their restitution stays the mix of their own.
  EXPECT_EQ(scene.response, ResponseMode::kPlausible);
  EXPECT_EQ(scene.sleep.time, 1.0f);
  expect_same_pairs(scene.pair_materials, {{.bodies = {1, 2}, .material = {0.9f, 0.3f}}});
}

TEST(SceneFileSchema, ListsTheKeysOfTheFormat) {
  const nlohmann::json schema = read_schema();
  EXPECT_EQ(schema.at("$schema"), "https://json-schema.org/draft/2020-12/schema");
  const nlohmann::json& defs = schema.at("$defs");
  const std::set<std::string> body_keys = [&] {
    std::set<std::string> keys = property_names(defs.at("body_settings"));
    keys.merge(property_names(defs.at("body")));
    return keys;
  }();

  // The full scene uses every key, and reads into the values above.
  const nlohmann::json full = nlohmann::json::parse(kFullScene);
  EXPECT_EQ(property_names(schema), object_keys(full));
  EXPECT_EQ(body_keys, object_keys(full.at("bodies").at(0)));
  EXPECT_EQ(property_names(defs.at("ground")), object_keys(full.at("ground")));
  EXPECT_EQ(property_names(defs.at("sphere_tree_build")),
            object_keys(full.at("bodies").at(0).at("sphere_tree")));
  EXPECT_EQ(property_names(defs.at("body")), (std::set<std::string>{"position", "orientation"}));
  EXPECT_EQ(property_names(defs.at("solver")), object_keys(full.at("solver")));
  EXPECT_EQ(property_names(defs.at("sleep")), object_keys(full.at("sleep")));
  EXPECT_EQ(property_names(defs.at("pair_material")), object_keys(full.at("pair_materials").at(0)));
  EXPECT_EQ(property_names(defs.at("joint")), object_keys(full.at("joints").at(0)));
  EXPECT_EQ(property_names(defs.at("robot")), object_keys(full.at("robots").at(0)));
  // The writer writes every key of a joint's parts.
  const nlohmann::json written = nlohmann::json::parse(scene_to_json(parse_scene(
      scene_text(R"("bodies": [{}], "joints": [{"type": "ball", "body_a": 0, "body_b": null}])"),
      "s.json")));
  for (const char* part : {"limit", "motor", "spring", "cone"}) {
    EXPECT_EQ(property_names(defs.at("joint").at("properties").at(part)),
              object_keys(written.at("joints").at(0).at(part)))
        << part;
  }
  EXPECT_EQ(schema.at("required"), nlohmann::json({"format", "version", "bodies"}));
}

// The defaults the schema gives for the world's settings: a default WorldSettings's.
TEST(SceneFileSchema, WorldSettingsDefaultsAreTheRuntimes) {
  const nlohmann::json schema = read_schema();
  const nlohmann::json& properties = schema.at("properties");
  const nlohmann::json& defs = schema.at("$defs");
  const Scene defaults = parse_scene(scene_text(R"("bodies": [])"), "s.json");
  const nlohmann::json written = nlohmann::json::parse(scene_to_json(defaults));
  for (const char* key : {"response", "paper_passes", "contacts", "collision_passes"}) {
    EXPECT_EQ(properties.at(key).at("default"), written.at(key)) << key;
  }
  const auto expect_defaults = [&](const char* def, const char* key) {
    for (const auto& item : defs.at(def).at("properties").items()) {
      EXPECT_EQ(item.value().at("default"), written.at(key).at(item.key()))
          << def << "/" << item.key();
    }
  };
  expect_defaults("solver", "solver");
  expect_defaults("sleep", "sleep");
}

TEST(SceneFileSchema, TheParserReadsEveryKeyItLists) {
  const nlohmann::json schema = read_schema();
  const nlohmann::json& defs = schema.at("$defs");
  // Sets `key` to a value no key accepts, inside `object` (a JSON pointer) of a scene whose other
  // members are `rest`: the parser must then complain about the value, not the key.
  const auto expect_read = [](std::string_view object, const std::string& key,
                              std::string_view rest) {
    nlohmann::json document = nlohmann::json::parse(scene_text(rest));
    document[nlohmann::json::json_pointer(std::string(object) + "/" + key)] =
        nlohmann::json::array({nlohmann::json::array()});
    const std::string text = document.dump();
    SCOPED_TRACE(text);
    EXPECT_THAT(parse_error(text),
                AllOf(StartsWith("scene.json: " + std::string(object) + "/" + key),
                      Not(HasSubstr("unknown key"))));
  };
  for (const std::string& key : property_names(schema)) {
    if (key != "format" && key != "version") expect_read("", key, R"("bodies": [])");
  }
  for (const std::string& key : property_names(defs.at("solver"))) {
    expect_read("/solver", key, R"("solver": {}, "bodies": [])");
  }
  for (const std::string& key : property_names(defs.at("sleep"))) {
    expect_read("/sleep", key, R"("sleep": {}, "bodies": [])");
  }
  for (const std::string& key : property_names(defs.at("pair_material"))) {
    expect_read("/pair_materials/0", key,
                R"("bodies": [{}, {}], "pair_materials": [{"bodies": [0, 1]}])");
  }
  constexpr std::string_view kJoint =
      R"("bodies": [{}, {}], "joints": [{"type": "ball", "body_a": 0, "body_b": 1)";
  for (const std::string& key : property_names(defs.at("joint"))) {
    expect_read("/joints/0", key, std::string(kJoint) + "}]");
  }
  for (const char* part : {"limit", "motor", "spring", "cone"}) {
    for (const std::string& key : property_names(defs.at("joint").at("properties").at(part))) {
      expect_read("/joints/0/" + std::string(part), key,
                  std::string(kJoint) + ", \"" + part + "\": {}}]");
    }
  }
  for (const std::string& key : property_names(defs.at("ground"))) {
    expect_read("/ground", key, R"("ground": {}, "bodies": [])");
  }
  for (const std::string& key : property_names(defs.at("body_settings"))) {
    expect_read("/defaults", key, R"("defaults": {}, "bodies": [])");
    expect_read("/bodies/0", key, R"("bodies": [{}])");
  }
  for (const std::string& key : property_names(defs.at("body"))) {
    expect_read("/bodies/0", key, R"("bodies": [{}])");
  }
  for (const std::string& key : property_names(defs.at("sphere_tree_build"))) {
    expect_read("/bodies/0/sphere_tree", key, R"("bodies": [{"sphere_tree": {}}])");
  }
}

}  // namespace
}  // namespace sphys::tools
