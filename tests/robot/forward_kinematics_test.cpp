// A robot's one forward kinematics: the poses worked out by hand for a planar arm, whatever its
// limits, and robot_link_poses the same poses once it has checked the values against them.

#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/robot_model.h"
#include "support/query_worlds.h"

namespace sphys::test {
namespace {

using testing::AllOf;
using testing::HasSubstr;

// Two links of 1 m and a slide along the second, each joint limited to [-0.5, 0.5].
RobotModel limited_arm() {
  RobotModel arm;
  arm.name = "limited";
  const Eigen::Isometry3d at_origin = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d one_metre_along_x(Eigen::Translation3d(1, 0, 0));
  arm.links = {{"base", -1, at_origin, -1},
               {"upper", 0, at_origin, 0},
               {"fore", 1, one_metre_along_x, 1},
               {"slider", 2, at_origin, 2}};
  for (const char* name : {"shoulder", "elbow"}) {
    arm.joints.push_back({name, RobotJointType::kRevolute, Eigen::Vector3d::UnitZ(), -0.5, 0.5});
  }
  arm.joints.push_back({"slide", RobotJointType::kPrismatic, Eigen::Vector3d::UnitX(), -0.5, 0.5});
  return arm;
}

TEST(ForwardKinematics, PosesAnyValuesWhereRobotLinkPosesChecksTheLimitsFirst) {
  const RobotModel arm = limited_arm();
  for (const std::vector<double>& values :
       {std::vector{0.3, -0.4, 0.2}, std::vector{2.0, -1.5, 3.0}}) {
    const std::vector<Eigen::Isometry3d> poses = forward_kinematics(arm, values);
    ASSERT_EQ(poses.size(), 4u);
    const double a = values[0];
    const double b = values[1];
    const double slide = values[2];
    const Eigen::Vector3d slider(std::cos(a) + slide * std::cos(a + b),
                                 std::sin(a) + slide * std::sin(a + b), 0.0);
    EXPECT_LT((poses[3].translation() - slider).norm(), 1e-12);
    EXPECT_LT(
        (poses[3].linear() - Eigen::Matrix3d(Eigen::AngleAxisd(a + b, Eigen::Vector3d::UnitZ())))
            .norm(),
        1e-12);
  }
  // Within the limits robot_link_poses gives the same bits; outside them it names the joint.
  const std::vector<double> inside = {0.3, -0.4, 0.2};
  const std::vector<Eigen::Isometry3d> checked = robot_link_poses(arm, inside);
  const std::vector<Eigen::Isometry3d> taken = forward_kinematics(arm, inside);
  for (std::size_t l = 0; l < checked.size(); ++l) {
    EXPECT_EQ(checked[l].matrix(), taken[l].matrix()) << l;
  }
  EXPECT_THAT(error_message([&] {
                (void)robot_link_poses(arm, std::vector{0.0, 1.5, 0.0});
              }),
              AllOf(HasSubstr("'elbow'"), HasSubstr("outside its limits")));
  EXPECT_THAT(error_message([&] {
                (void)forward_kinematics(arm, std::vector{0.0, 0.0});
              }),
              HasSubstr("2 joint values for 3 joints"));
}

}  // namespace
}  // namespace sphys::test
