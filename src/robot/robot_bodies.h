#pragma once

// A robot model's links grouped into the bodies a world simulates: one per link a joint moves,
// carrying the links fixed to it (their masses, inertias and spheres merged, as MuJoCo fuses
// static bodies), and the root link's.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sphys/robot_model.h"
#include "sphys/sphere_tree.h"

namespace sphys {

// One body of a robot: its mass properties and tree in its frame, whose origin is its centre of
// mass and whose axes are its own link's.
struct RobotBodyPlan {
  std::int32_t link = 0;  // the link it is made for: the root, or the link a joint moves
  double mass = 0.0;      // unit: kg
  // The centre of mass in its link's frame. unit: m
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre. unit: kg·m²
  std::shared_ptr<const SphereTree> tree;             // the links' spheres, body frame
};

struct RobotPlan {
  std::vector<RobotBodyPlan> bodies;  // [0] the root's, [j + 1] joint j's link's
  // Per link: its body, and its frame in the body's frame (RobotBodyPlan). unit: m
  std::vector<std::uint32_t> link_body;
  std::vector<Eigen::Isometry3d> link_in_body;
};

// Throws sphys::Error naming the link for a body (but a fixed root's) with no mass or no
// spheres.
[[nodiscard]] RobotPlan plan_robot_bodies(const RobotModel& model, bool fixed_root);

// A tree over the spheres (positive radii) as its leaves, all on its last level: each level
// splits its spheres into up to 8 runs along the longest extent of their centres, each node
// bounding the spheres under it. Throws sphys::Error for no sphere.
[[nodiscard]] SphereTree tree_over_spheres(std::span<const Sphere> leaves);

}  // namespace sphys
