#pragma once

// A scene: what a simulation starts from. Read from JSON scene files (docs/scenes.md,
// docs/scene.schema.json) or made by the built-in presets (sphys/tools/scenarios.h).

#include <array>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/math.h"
#include "sphys/tools/build_tree.h"
#include "sphys/world.h"

namespace sphys::tools {

// Where a body's sphere-tree comes from: a .sph file, or built from the body's mesh.
struct TreeSpec {
  std::optional<std::filesystem::path> sph_file;  // in the body frame (centre of mass at 0)
  BuildMethod method = BuildMethod::Combined;     // how it is built, without sph_file
  int branching = 8;                              // 2..8
  int depth = 3;                                  // levels including the root, 1..6
};

// Most bodies a scene may hold, in a file or a preset: a million bunnies is twenty times the
// largest heap sphys is measured on, and the cap keeps a small file (3 bytes a body, "{},") from
// asking for gigabytes before anything is simulated. unit: bodies
inline constexpr std::size_t kMaxSceneBodies = 1'000'000;

// A body's mass, given or made from its density and volume: from a 1 mg grain to a 10⁹ kg
// building (docs/scenes.md, "Values"). unit: kg
inline constexpr double kMinBodyMass = 1e-6;
inline constexpr double kMaxBodyMass = 1e9;  // unit: kg

// One body of a scene: its mesh, size, tree, initial state and material.
struct BodySpec {
  // "bunny" (the default model) or a mesh file (relative paths are relative to the scene file).
  std::string mesh = "bunny";
  // Triangle budget for decimation; unset: the model's default for "bunny", none for files.
  std::optional<std::size_t> triangles;
  // Longest side of the bounding box after uniform scaling; unset keeps the mesh's size. unit: m
  std::optional<double> size = 1.0;
  TreeSpec tree;                         // where its sphere-tree comes from
  Vec3 position = Vec3::Zero();          // of the centre of mass. unit: m
  Quat orientation = Quat::Identity();   // body frame to world; unit length
  Vec3 linear_velocity = Vec3::Zero();   // unit: m/s
  Vec3 angular_velocity = Vec3::Zero();  // unit: rad/s
  double density = 1000.0;               // unit: kg/m³
  std::optional<double> mass;            // overrides density·volume (inertia scales). unit: kg
  float restitution = BodyDesc{}.restitution;  // unit: dimensionless, 0..1
  float friction = BodyDesc{}.friction;        // Coulomb coefficient. unit: dimensionless
  bool is_static = false;                      // never moves (its mass is not used)
};

// What a scene stands on.
struct GroundSpec {
  // The ground's shape.
  enum class Kind {
    kNone,       // no ground
    kPlane,      // the exact half-space y <= height
    kOctreeBox,  // the paper's plane: a thin box's octree sphere-tree, top face at y = height
  };
  Kind kind = Kind::kOctreeBox;  // the paper's ground by default
  double height = 0.0;           // unit: m
  double size = 16.0;            // side of the box's top face (kOctreeBox). unit: m
  double thickness = 0.5;        // unit: m
  int depth = 5;                 // levels of the box's octree
  float restitution = WorldSettings{}.ground_restitution;  // unit: dimensionless, 0..1
  float friction = WorldSettings{}.ground_friction;  // Coulomb coefficient. unit: dimensionless
};

// The friction and restitution of contacts between two of the scene's bodies
// (World::set_pair_material), instead of the mix of their own.
struct PairMaterialSpec {
  std::array<std::size_t, 2> bodies{};  // indices into Scene::bodies, different
  PairMaterial material;                // what their contacts use
};

// A joint between two of the scene's bodies, or a body and the world (World::add_joint).
struct JointSpec {
  // Indices into Scene::bodies; none: the world. At least one is a body, and not both the same.
  std::optional<std::size_t> body_a;
  std::optional<std::size_t> body_b;  // as body_a
  JointDesc desc;  // everything else (its body ids unused: build_world sets them)
};

// A robot of the scene (World::add_robot, docs/robots.md), added after the joints by
// tools::add_scene_robots (sphys/tools/scene_robots.h): its files, where its root link stands, its
// joint values at the start and the targets position control holds them to.
struct SceneRobot {
  // Paths as written: a relative one is taken from Scene::base_directory.
  std::filesystem::path urdf;
  std::filesystem::path spheres;  // what `sphys spherize` wrote for it, any of its formats
  std::optional<std::filesystem::path> srdf;  // its disabled collision pairs, if any
  // Where `package://NAME/...` meshes of the URDF are: NAME's folder, by NAME.
  std::map<std::string, std::filesystem::path> packages;
  Vec3 position = Vec3::Zero();         // the root link in the world. unit: m
  Quat orientation = Quat::Identity();  // the root link's axes in the world
  bool fixed_base = true;               // RobotBase::kFixed, else kFree
  // One value per joint, in the model's order; empty: every joint at 0. unit: rad or m
  std::vector<double> configuration;
  // Position control's targets, one per joint; empty: the robot is limp. unit: rad or m
  std::vector<double> targets;
};

// "paper", "plausible": the response modes by name, as scene files and the command line write
// them.
[[nodiscard]] std::string_view response_mode_name(ResponseMode mode);
// Throws sphys::Error listing the valid names.
[[nodiscard]] ResponseMode parse_response_mode(std::string_view name);
// The ground options: "octree" (the paper's octree ground) and "plane". Throws sphys::Error
// "<option> must be octree or plane, got '<name>'", the option as its front end names it.
[[nodiscard]] GroundSpec::Kind parse_ground_option(std::string_view name,
                                                   std::string_view option = "--ground");
// "all", "reduced": the contact sets by name.
[[nodiscard]] std::string_view contact_set_name(ContactSet contacts);
// Throws sphys::Error listing the valid names.
[[nodiscard]] ContactSet parse_contact_set(std::string_view name);

// The world's settings start from a default WorldSettings, so that a scene that leaves a key out
// runs as the runtime would by default. Their ranges and units are those of the settings table
// (sphys/settings_table.h).
struct Scene {
  std::string name;                        // the file name or the preset, for reports
  Vec3 gravity = WorldSettings{}.gravity;  // unit: m/s²
  // Between frames, one step each. unit: s
  double time_step = 1.0 / 60.0;
  int frames = 880;                                  // one step per frame
  ResponseMode response = WorldSettings{}.response;  // WorldSettings::response
  // WorldSettings::paper_passes. unit: passes
  int paper_passes = static_cast<int>(WorldSettings{}.paper_passes);
  // WorldSettings' collision passes per frame, at least and at most, and the travel per pass
  // that decides between them (unit: bounding radii).
  int collision_passes = static_cast<int>(WorldSettings{}.collision_passes);
  int max_collision_passes = static_cast<int>(WorldSettings{}.max_collision_passes);  // at most
  float collision_pass_travel = WorldSettings{}.collision_pass_travel;  // unit: bounding radii
  SolverSettings solver;         // plausible mode; solver.contacts is the scene's "contacts"
  SleepSettings sleep;           // plausible mode
  GroundSpec ground;             // what the bodies stand on
  std::vector<BodySpec> bodies;  // at most kMaxSceneBodies
  std::vector<PairMaterialSpec> pair_materials;  // pairs of bodies with their own material
  std::vector<JointSpec> joints;                 // added after the bodies, in order
  std::vector<SceneRobot> robots;                // added after the joints, in order
  // Folder that relative mesh and .sph paths are taken from.
  std::filesystem::path base_directory;
};

// The world's settings the scene carries, over a default WorldSettings (threads and the
// detection budgets are not a scene's). A negative count becomes 0, which World refuses by name.
[[nodiscard]] WorldSettings world_settings(const Scene& scene);
// The other way: the scene's fields from those settings.
void set_world_settings(Scene& scene, const WorldSettings& settings);

}  // namespace sphys::tools
