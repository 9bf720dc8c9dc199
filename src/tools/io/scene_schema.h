#pragma once

// The scene format's manifest, shared by its reader and its writer: the format's name and
// version, the keys of each object, the names of the ground's kinds and the limits of every
// figure. docs/scenes.md and docs/scene.schema.json describe the same; the world's settings,
// which scenes carry too, are the settings table's (sphys/settings_table.h).

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <utility>

#include "json_values.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {

inline constexpr std::string_view kSceneFormat = "sphys-scene";
inline constexpr long long kSceneVersion = 1;

inline constexpr long long kMaxFrames = 10'000'000;
inline constexpr long long kMaxTriangles = 4'294'967'295;  // 2^32 - 1, beyond any mesh sphys loads
inline constexpr long long kMinTriangles = 4;  // a tetrahedron, the smallest closed mesh
inline constexpr long long kMaxGroundDepth = 7;
inline constexpr long long kMaxTreeDepth = 6;

// The physical figures a scene may give: wide enough for any rigid body from a grain (1 mm,
// 1 mg) to a building (1 km, 10^9 kg), narrow enough that every product the simulation forms
// from them (a mass from density and volume, an inertia from mass and size squared, a step's
// travel from speed and time step) stays finite and normal in single precision, so nothing
// accepted here fails later (docs/scenes.md lists them).
inline constexpr PhysicalRange kTimeStepRange{1e-6, 1.0, "s"};
inline constexpr PhysicalRange kBodySizeRange{1e-3, 1e3, "m"};
inline constexpr PhysicalRange kDensityRange{1e-3, 1e6, "kg/m³"};
inline constexpr PhysicalRange kMassRange{kMinBodyMass, kMaxBodyMass, "kg"};
inline constexpr PhysicalRange kGroundSizeRange{1e-2, 1e5, "m"};
inline constexpr PhysicalRange kGroundThicknessRange{1e-3, 1e4, "m"};
// Coordinates beyond this lose centimetres in single precision. unit: m
inline constexpr double kMaxCoordinate = 1e5;
// Beyond any rigid body's speed (a rifle bullet: 1,000 m/s). unit: m/s; rad/s for spin
inline constexpr double kMaxSpeed = 1e4;
// A distance joint's length, from a micrometre to the farthest coordinate. unit: m
inline constexpr PhysicalRange kJointLengthRange{1e-6, kMaxCoordinate, "m"};

inline constexpr std::array<std::string_view, 3> kPairMaterialKeys = {"bodies", "friction",
                                                                      "restitution"};
inline constexpr std::array<std::string_view, 14> kJointKeys = {
    "type",  "body_a", "body_b", "anchor_a", "anchor_b", "axis_a", "axis_b",
    "limit", "motor",  "spring", "cone",     "friction", "length", "collide_connected"};
inline constexpr std::array<std::string_view, 3> kJointLimitKeys = {"enabled", "lower", "upper"};
inline constexpr std::array<std::string_view, 3> kJointMotorKeys = {"enabled", "speed",
                                                                    "max_effort"};
inline constexpr std::array<std::string_view, 4> kJointSpringKeys = {"enabled", "hertz",
                                                                     "damping_ratio", "target"};
inline constexpr std::array<std::string_view, 2> kJointConeKeys = {"enabled", "angle"};
inline constexpr std::array<std::string_view, 9> kRobotKeys = {
    "urdf",        "spheres",    "srdf",          "packages", "position",
    "orientation", "fixed_base", "configuration", "targets"};
inline constexpr std::array<std::string_view, 13> kBodyKeys = {"mesh",
                                                               "triangles",
                                                               "size",
                                                               "sphere_tree",
                                                               "position",
                                                               "orientation",
                                                               "linear_velocity",
                                                               "angular_velocity",
                                                               "density",
                                                               "mass",
                                                               "restitution",
                                                               "friction",
                                                               "static"};
// Set per body only: a shared position or orientation would stack every body in one place.
inline constexpr std::array<std::string_view, 2> kPerBodyKeys = {"position", "orientation"};
inline constexpr std::array<std::string_view, 3> kTreeKeys = {"method", "branching", "depth"};
inline constexpr std::array<std::string_view, 4> kQuaternionKeys = {"w", "x", "y", "z"};
inline constexpr std::array<std::string_view, 1> kYawKeys = {"yaw_degrees"};
inline constexpr std::array<std::string_view, 2> kAxisAngleKeys = {"axis", "angle_degrees"};
inline constexpr std::array<std::string_view, 7> kOrientationKeys = {
    "w", "x", "y", "z", "yaw_degrees", "axis", "angle_degrees"};

// The keys of the top level and of "ground": their own and the world settings they carry.
[[nodiscard]] std::span<const std::string_view> scene_keys();
[[nodiscard]] std::span<const std::string_view> ground_keys();
// The keys of "solver" or "sleep": world settings only.
[[nodiscard]] std::span<const std::string_view> setting_keys(std::string_view object);

template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<Enum, std::string_view>, N>;

inline constexpr NameTable<GroundSpec::Kind, 3> kGroundKinds{{
    {GroundSpec::Kind::kOctreeBox, "octree-box"},
    {GroundSpec::Kind::kPlane, "plane"},
    {GroundSpec::Kind::kNone, "none"},
}};

inline constexpr NameTable<JointType, 5> kJointTypes{{
    {JointType::kHinge, "hinge"},
    {JointType::kSlider, "slider"},
    {JointType::kBall, "ball"},
    {JointType::kWeld, "weld"},
    {JointType::kDistance, "distance"},
}};

template <typename Enum, std::size_t N>
[[nodiscard]] std::string_view name_of(Enum value, const NameTable<Enum, N>& table) {
  for (const auto& [entry, name] : table) {
    if (entry == value) return name;
  }
  return "unknown";
}

}  // namespace sphys::tools
