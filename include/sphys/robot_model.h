#pragma once

// A robot as a motion planner's checks need it: a chain (a tree) of links moved by joints, and the
// spheres on each link, compiled into flat arrays so that the poses of many configurations of joint
// values are computed together (robot_check.h). Made from a URDF and the spheres `sphys spherize`
// wrote by tools::load_robot_model (sphys/tools/robot_model_file.h), or by hand.

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"

namespace sphys {

// How a joint moves its link.
enum class RobotJointType : std::uint8_t {
  kRevolute,    // turns about its axis by the joint value (rad), within its limits
  kContinuous,  // turns without limits (rad)
  kPrismatic,   // slides along its axis by the joint value (m), within its limits
};

// A robot's links, joints and spheres (the top of this file says where it comes from).
struct RobotModel {
  // A link of the chain. Links are listed parents first; link 0 is the root.
  struct Link {
    std::string name;          // what link_index looks up (the URDF's link name)
    std::int32_t parent = -1;  // the link it hangs from; -1 for the root
    // The link's frame in its parent's at joint value 0 (a fixed joint's whole pose). unit: m
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
    // The joint that moves it: its index in joints, or -1 where it is fixed to its
    // parent.
    std::int32_t joint = -1;
    // Its mass (the URDF's `inertial` element); 0 for none. A simulated robot (World::add_robot)
    // needs mass on every link its joints move, counting the links fixed to it. unit: kg
    double mass = 0.0;
    // Its centre of mass in its frame. unit: m
    Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
    // Its inertia about its centre of mass, in its frame's axes. unit: kg·m²
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    // The URDF gave no `inertial` element: mass, centre and inertia are its geometry's at
    // tools::kDefaultLinkDensity (sphys/tools/robot_model_file.h).
    bool mass_from_geometry = false;
  };

  // A joint that moves one link; fixed joints are no Joint (Link::joint -1).
  struct Joint {
    std::string name;                                 // as the URDF names it, if from one
    RobotJointType type = RobotJointType::kRevolute;  // how it moves its link
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // a unit vector in the moved link's frame
    double lower = 0.0;  // limits, unit: rad or m (both infinite for a continuous joint)
    double upper = 0.0;  // unit: rad or m
    // The most torque or force a simulated joint applies (the URDF's effort), > 0. unit: N·m
    // or N
    double effort = std::numeric_limits<double>::infinity();
    // The fastest a simulated joint's position control drives it (the URDF's velocity), > 0.
    // unit: rad/s or m/s
    double velocity = std::numeric_limits<double>::infinity();
  };

  std::string name;           // as the URDF names it, if from one
  std::vector<Link> links;    // parents first; link 0 is the root
  std::vector<Joint> joints;  // a configuration holds one value per joint, in this order
  // Each sphere's link and the sphere in that link's frame. unit: m
  std::vector<std::int32_t> sphere_links;
  std::vector<Sphere> spheres;  // one per entry of sphere_links, in its link's frame. unit: m
  // Pairs of links whose spheres are never checked against each other (SRDF's disabled
  // collisions: neighbours, links that can never meet); a link is never checked against itself.
  std::vector<std::array<std::int32_t, 2>> allowed_link_pairs;
  // The root link in the world. unit: m
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();

  // The index of the link named so; throws sphys::Error naming a link the model does not have.
  [[nodiscard]] std::int32_t link_index(std::string_view link) const;
};

// Throws sphys::Error naming what is wrong: no link, a parent that is not listed before its
// child, a joint used by two links or by none, a joint axis that is not a unit vector, limits
// that are not finite (continuous joints: not infinite) or lower > upper, a sphere on no link or
// with a negative or non-finite radius, an allowed pair naming no link, a non-finite pose.
void check_robot_model(const RobotModel& model);

// Throws sphys::Error naming the configuration and joint of the first value that is NaN, infinite
// or outside its joint's limits, and `what` (the argument) when `values` is no whole number of
// configurations of the model's joints.
void check_joint_values(const RobotModel& model, std::span<const double> values,
                        std::string_view what);

// Every link's pose in the world for one configuration, in double: the reference the batched
// float kinematics are checked against. `values`: one per joint; throws sphys::Error naming the
// joint whose value is NaN or outside its limits.
[[nodiscard]] std::vector<Eigen::Isometry3d> robot_link_poses(const RobotModel& model,
                                                              std::span<const double> values);

// The same poses with each value taken as it is, its limits unchecked (robot_link_poses checks
// them): the one forward kinematics, which tools::link_poses poses a URDF's links by too.
// `values`: one per joint, finite; throws sphys::Error for another count.
[[nodiscard]] std::vector<Eigen::Isometry3d> forward_kinematics(const RobotModel& model,
                                                                std::span<const double> values);

}  // namespace sphys
