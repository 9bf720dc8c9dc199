#pragma once

// The test robot's arm (tests/support/test_robot.h) as a planner sees it: its moving joints with
// their limits, its links' spheres from `spherize`, and the spheres posed for joint values, in a
// y-up world where the robot's base stands at `base` (the URDF's z axis turned up to y).

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/spherize.h"
#include "sphys/world_query.h"

namespace sphys::examples {

struct RobotArm {
  tools::Robot robot;
  std::vector<tools::LinkSpheres> links;      // the links with spheres, spherize's order
  std::vector<std::string> joints;            // the moving joints, in the URDF's order
  std::vector<std::array<double, 2>> limits;  // per joint: lower, upper (rad or m)
  std::vector<std::int32_t> sphere_links;     // per sphere: its index in `links`
  std::vector<Sphere> link_spheres;           // per sphere, in its link's frame. unit: m
  Transform base;                             // the root link in the world

  [[nodiscard]] std::size_t spheres() const { return sphere_links.size(); }
  // Each of `links`' poses in the world for the joint values (one per joint). unit: m
  void link_poses(std::span<const double> values, std::span<Transform> out) const;
  // The spheres in the world: spheres() × (x, y, z, radius). unit: m
  void posed_spheres(std::span<const double> values, std::span<float> out) const;
  // The meshes of `links`, each in its link's frame, in their order.
  [[nodiscard]] std::vector<tools::TriangleMesh> link_meshes() const;
};

// Writes the test robot into `dir`, reads it back and spherizes it to `total_spheres` spheres.
[[nodiscard]] RobotArm make_test_robot_arm(const std::filesystem::path& dir, int total_spheres,
                                           const Vec3& base_position);

// Stands the arm's base on the ground (y = 0) as near to `centre` as it can along +x: from
// `centre` outward in 5 cm steps to the first place where the arm, upright (every joint at 0),
// is free, then `clearance` farther. Many of its reaches then end in what is around `centre`.
void place_arm_beside(RobotArm& arm, const WorldQuery& query, const Vec3& centre, float clearance);

}  // namespace sphys::examples
