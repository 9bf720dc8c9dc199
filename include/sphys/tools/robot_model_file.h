#pragma once

// A RobotModel (sphys/robot_model.h) from a robot's files: its URDF, the spheres `sphys spherize`
// wrote for it (cuRobo's YAML, MoveIt's SRDF or a spherized URDF) and, for self-collision, the
// pairs of links an SRDF's disable_collisions elements name.

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sphys/robot_model.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/spherize.h"

namespace sphys::tools {

// The density a link without an `inertial` element is given its mass by, from its collision (or
// visual) mesh (RobotModel::Link::mass_from_geometry): water's, about a plastic's. unit: kg/m³
inline constexpr double kDefaultLinkDensity = 1000.0;

// The model of a loaded robot with its links' spheres: every link of the URDF (those without
// geometry or spheres too), parents first, breadth first from the root, siblings by name; its
// moving joints in the same order (a chain's from the base out). Each link's mass from its
// `inertial` element, or else from its geometry at kDefaultLinkDensity (a link with neither has
// none). `disabled`: pairs of link names never checked against each other. Throws sphys::Error
// naming the file and the joint for a mimic, floating or planar joint, and the link for spheres on
// a link the robot does not have.
[[nodiscard]] RobotModel robot_model(const Robot& robot, std::span<const LinkSpheres> links,
                                     std::span<const std::array<std::string, 2>> disabled = {});

// The pairs of links an SRDF's <disable_collisions link1="..." link2="..."/> elements name.
// Throws sphys::Error naming the file and line for XML that does not parse or an element without
// both links.
[[nodiscard]] std::vector<std::array<std::string, 2>> read_disabled_collisions(
    const std::filesystem::path& srdf);

// load_robot, read_robot_spheres and (with `srdf`) read_disabled_collisions, then robot_model.
[[nodiscard]] RobotModel load_robot_model(const std::filesystem::path& urdf,
                                          const std::filesystem::path& spheres,
                                          std::span<const RobotPackage> packages = {},
                                          const std::optional<std::filesystem::path>& srdf = {});

// A robot as its files describe it: the URDF's links with their meshes, for drawing, and the
// model made of them with its spheres, for simulation.
struct LoadedRobot {
  Robot robot;       // as load_robot read it
  RobotModel model;  // as load_robot_model makes it
};

// load_robot_model, keeping the robot it read.
[[nodiscard]] LoadedRobot load_robot_files(const std::filesystem::path& urdf,
                                           const std::filesystem::path& spheres,
                                           std::span<const RobotPackage> packages = {},
                                           const std::optional<std::filesystem::path>& srdf = {});

}  // namespace sphys::tools
