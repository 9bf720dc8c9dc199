// A robot model's own checks: its links, joints, limits and spheres, and joint values against
// them (its forward kinematics: forward_kinematics.cpp).

#include "sphys/robot_model.h"

#include <cmath>
#include <string>

#include "sphys/error.h"

namespace sphys {
namespace {

// How far from 1 a joint axis's length may be. unit: dimensionless
constexpr double kUnitAxisTolerance = 1e-6;

bool finite(const Eigen::Isometry3d& pose) { return pose.matrix().allFinite(); }

std::string joint_text(const RobotModel& model, std::size_t joint) {
  return "joint " + std::to_string(joint) + " ('" + model.joints[joint].name + "')";
}

}  // namespace

std::int32_t RobotModel::link_index(std::string_view link) const {
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (links[l].name == link) return static_cast<std::int32_t>(l);
  }
  throw Error("the robot '" + name + "' has no link '" + std::string(link) + "'");
}

void check_robot_model(const RobotModel& model) {
  if (model.links.empty()) throw Error("robot '" + model.name + "': no links");
  if (!finite(model.base)) throw Error("robot '" + model.name + "': the base pose is not finite");
  std::vector<int> joint_users(model.joints.size(), 0);
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    const std::string what = "link " + std::to_string(l) + " ('" + link.name + "')";
    if (l == 0 ? link.parent != -1 : link.parent < 0 || link.parent >= static_cast<int>(l)) {
      throw Error(what + ": its parent must be listed before it (the root, link 0, has none)");
    }
    if (!finite(link.origin)) throw Error(what + ": its origin is not finite");
    if (link.joint >= static_cast<std::int32_t>(model.joints.size()) || link.joint < -1) {
      throw Error(what + ": no joint " + std::to_string(link.joint));
    }
    if (!std::isfinite(link.mass) || link.mass < 0.0 || !link.center_of_mass.allFinite() ||
        !link.inertia.allFinite()) {
      throw Error(what + ": its mass must be finite and not negative, its centre of mass and " +
                  "inertia finite");
    }
    if (link.joint >= 0) {
      if (l == 0) throw Error(what + ": the root link has no joint");
      ++joint_users[static_cast<std::size_t>(link.joint)];
    }
  }
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const RobotModel::Joint& joint = model.joints[j];
    if (joint_users[j] != 1) {
      throw Error(joint_text(model, j) + ": moves " + std::to_string(joint_users[j]) +
                  " links, not 1");
    }
    if (!joint.axis.allFinite() || std::abs(joint.axis.norm() - 1.0) > kUnitAxisTolerance) {
      throw Error(joint_text(model, j) + ": its axis is not a unit vector");
    }
    if (!(joint.effort > 0.0) || !(joint.velocity > 0.0)) {
      throw Error(joint_text(model, j) + ": its effort and velocity bounds must be positive " +
                  "(infinite for none)");
    }
    if (joint.type == RobotJointType::kContinuous) {
      if (!(std::isinf(joint.lower) && joint.lower < 0 && std::isinf(joint.upper) &&
            joint.upper > 0)) {
        throw Error(joint_text(model, j) + ": a continuous joint has no limits (-inf, inf)");
      }
    } else if (!std::isfinite(joint.lower) || !std::isfinite(joint.upper) ||
               joint.lower > joint.upper) {
      throw Error(joint_text(model, j) + ": its limits must be finite with lower <= upper, got " +
                  std::to_string(joint.lower) + " .. " + std::to_string(joint.upper));
    }
  }
  if (model.sphere_links.size() != model.spheres.size()) {
    throw Error("robot '" + model.name + "': " + std::to_string(model.sphere_links.size()) +
                " sphere links for " + std::to_string(model.spheres.size()) + " spheres");
  }
  if (model.spheres.empty()) throw Error("robot '" + model.name + "': no spheres");
  for (std::size_t s = 0; s < model.spheres.size(); ++s) {
    const Sphere& sphere = model.spheres[s];
    if (model.sphere_links[s] < 0 ||
        model.sphere_links[s] >= static_cast<std::int32_t>(model.links.size())) {
      throw Error("sphere " + std::to_string(s) + ": no link " +
                  std::to_string(model.sphere_links[s]));
    }
    if (!sphere.center.allFinite() || !std::isfinite(sphere.radius) || sphere.radius < 0.0f) {
      throw Error("sphere " + std::to_string(s) +
                  ": its centre must be finite and its radius finite and not negative");
    }
  }
  for (const auto& [a, b] : model.allowed_link_pairs) {
    const auto count = static_cast<std::int32_t>(model.links.size());
    if (a < 0 || b < 0 || a >= count || b >= count) {
      throw Error("allowed link pair (" + std::to_string(a) + ", " + std::to_string(b) +
                  ") names a link the robot does not have");
    }
  }
}

void check_joint_values(const RobotModel& model, std::span<const double> values,
                        std::string_view what) {
  const std::size_t joints = model.joints.size();
  if (joints == 0 ? !values.empty() : values.size() % joints != 0) {
    throw Error(std::string(what) + ": " + std::to_string(values.size()) +
                " values is no whole number of configurations of " + std::to_string(joints) +
                " joints");
  }
  // Configuration by configuration, joint by joint: no division per value.
  for (std::size_t i = 0, j = 0; i < values.size(); ++i, j = j + 1 == joints ? 0 : j + 1) {
    const RobotModel::Joint& joint = model.joints[j];
    const double value = values[i];
    if (!std::isfinite(value) || value < joint.lower || value > joint.upper) {
      throw Error(std::string(what) + ": configuration " + std::to_string(i / joints) +
                  ", joint '" + joint.name + "': " + std::to_string(value) +
                  (std::isfinite(value) ? " is outside its limits " + std::to_string(joint.lower) +
                                              " .. " + std::to_string(joint.upper)
                                        : " is not finite"));
    }
  }
}

}  // namespace sphys
