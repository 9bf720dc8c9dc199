#include "robot_arm.h"

#include <algorithm>
#include <map>
#include <numbers>

#include "sphys/configuration_check.h"
#include "sphys/error.h"
#include "support/test_robot.h"

namespace sphys::examples {

RobotArm make_test_robot_arm(const std::filesystem::path& dir, int total_spheres,
                             const Vec3& base_position) {
  const test::RobotSpec spec = test::standard_test_robot();
  const test::TestRobot written = test::write_test_robot(dir, spec);
  RobotArm arm;
  const tools::RobotPackage package = tools::parse_robot_package(written.package_option);
  arm.robot = tools::load_robot(written.urdf, std::span(&package, 1));
  tools::SpherizeOptions options;
  options.total_spheres = total_spheres;
  arm.links = tools::spherize(arm.robot, options);
  for (const test::RobotJointSpec& joint : spec.joints) {
    if (joint.type == "fixed") continue;
    arm.joints.push_back(joint.name);
    arm.limits.push_back({joint.lower, joint.upper});
  }
  for (std::size_t l = 0; l < arm.links.size(); ++l) {
    for (const Sphere& sphere : arm.links[l].spheres) {
      arm.sphere_links.push_back(static_cast<std::int32_t>(l));
      arm.link_spheres.push_back(sphere);
    }
  }
  // The URDF's z up turned to the world's y up: a quarter turn about x.
  arm.base.rotation = Quat(Eigen::AngleAxisf(-std::numbers::pi_v<float> / 2, Vec3::UnitX()));
  arm.base.translation = base_position;
  return arm;
}

void RobotArm::link_poses(std::span<const double> values, std::span<Transform> out) const {
  std::map<std::string, double> named;
  for (std::size_t j = 0; j < joints.size(); ++j) named[joints[j]] = values[j];
  const std::map<std::string, tools::Pose3d> poses = tools::link_poses(robot, named);
  for (std::size_t l = 0; l < links.size(); ++l) {
    const tools::Pose3d& pose = poses.at(links[l].link);
    const Transform in_root{Quat(pose.linear().cast<float>()), pose.translation().cast<float>()};
    out[l] = {base.rotation * in_root.rotation, base.apply(in_root.translation)};
  }
}

void RobotArm::posed_spheres(std::span<const double> values, std::span<float> out) const {
  std::vector<Transform> poses(links.size());
  link_poses(values, poses);
  for (std::size_t i = 0; i < spheres(); ++i) {
    const Vec3 centre =
        poses[static_cast<std::size_t>(sphere_links[i])].apply(link_spheres[i].center);
    out[4 * i] = centre.x();
    out[4 * i + 1] = centre.y();
    out[4 * i + 2] = centre.z();
    out[4 * i + 3] = link_spheres[i].radius;
  }
}

std::vector<tools::TriangleMesh> RobotArm::link_meshes() const {
  std::vector<tools::TriangleMesh> out;
  for (const tools::LinkSpheres& link : links) {
    const auto geometry =
        std::find_if(robot.links.begin(), robot.links.end(),
                     [&](const tools::LinkGeometry& g) { return g.link == link.link; });
    out.push_back(geometry->mesh);
  }
  return out;
}

void place_arm_beside(RobotArm& arm, const WorldQuery& query, const Vec3& centre, float clearance) {
  constexpr float kStep = 0.05f;    // unit: m
  constexpr int kMostSteps = 1000;  // 50 m
  const ConfigurationChecker checker(query, arm.sphere_links);
  const std::vector<double> upright(arm.joints.size(), 0.0);
  std::vector<float> spheres(arm.spheres() * 4);
  std::vector<ConfigurationResult> result(1);
  for (int step = 0; step < kMostSteps; ++step) {
    arm.base.translation = Vec3(centre.x() + kStep * static_cast<float>(step), 0.0f, centre.z());
    arm.posed_spheres(upright, spheres);
    checker.check(spheres, result);
    if (result[0].free) {
      arm.base.translation.x() += clearance;
      return;
    }
  }
  throw Error("no free place for the arm's base within 50 m of the centre");
}

}  // namespace sphys::examples
