// How far a link's spheres can move with the joints (robot/robot_sweep.h): the rates of a chain
// worked out by hand, and the bound against the double kinematics along random motions.

#include "robot/robot_sweep.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace sphys::test {
namespace {

constexpr double kHalfTurn = std::numbers::pi;  // unit: rad

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(x, y, z));
  return pose;
}

// A fixed base at the origin; `turn` about z at the base's origin, a sphere 1 m out on x; `slide`
// along x from 1 m out on `turn`'s link, -0.2 to 0.5 m, a sphere 0.5 m out; `twist` about x from
// 1 m up on `slide`'s link, a sphere 0.3 m out on y.
RobotModel chain() {
  RobotModel model;
  model.name = "chain";
  model.links = {{"base", -1, Eigen::Isometry3d::Identity(), -1},
                 {"arm", 0, Eigen::Isometry3d::Identity(), 0},
                 {"slider", 1, at(1, 0, 0), 1},
                 {"hand", 2, at(0, 0, 1), 2}};
  model.joints = {
      {"turn", RobotJointType::kRevolute, Eigen::Vector3d::UnitZ(), -kHalfTurn, kHalfTurn},
      {"slide", RobotJointType::kPrismatic, Eigen::Vector3d::UnitX(), -0.2, 0.5},
      {"twist", RobotJointType::kRevolute, Eigen::Vector3d::UnitX(), -2.0, 2.0}};
  model.sphere_links = {1, 2, 3};
  model.spheres = {{Vec3(1.0f, 0.0f, 0.0f), 0.1f},
                   {Vec3(0.5f, 0.0f, 0.0f), 0.1f},
                   {Vec3(0.0f, 0.3f, 0.0f), 0.05f}};
  return model;
}

// The most a centre of `link` moves for a change of one joint alone.
double rate(const LinkSweep& sweep, std::size_t link, std::size_t joint) {
  std::vector<double> changes(3, 0.0);
  changes[joint] = 1.0;
  return sweep.along(link, changes);
}

TEST(LinkSweep, ARateIsTheFarthestReachFromTheAxisOrOneForASlide) {
  const LinkSweep sweep(chain());
  // The arm's sphere is 1 m from the turn's axis; nothing else moves it.
  EXPECT_DOUBLE_EQ(rate(sweep, 1, 0), 1.0);
  EXPECT_DOUBLE_EQ(rate(sweep, 1, 1), 0.0);
  EXPECT_DOUBLE_EQ(rate(sweep, 1, 2), 0.0);
  // The slider's sphere: 0.5 m out, slid up to 0.5 m, 1 m from the turn's axis point.
  EXPECT_DOUBLE_EQ(rate(sweep, 2, 0), 2.0);
  EXPECT_DOUBLE_EQ(rate(sweep, 2, 1), 1.0);
  EXPECT_DOUBLE_EQ(rate(sweep, 2, 2), 0.0);
  // The hand's: 0.3 m from the twist's axis, then 1 m up, the slide, 1 m out.
  EXPECT_NEAR(rate(sweep, 3, 2), 0.3, 1e-6);  // 0.3 as a float
  EXPECT_DOUBLE_EQ(rate(sweep, 3, 1), 1.0);
  EXPECT_NEAR(rate(sweep, 3, 0), 2.8, 1e-6);
  // The base moves with nothing; changes add up.
  EXPECT_DOUBLE_EQ(sweep.along(0, std::vector{1.0, 1.0, 1.0}), 0.0);
  EXPECT_NEAR(sweep.along(3, std::vector{0.5, 0.25, 2.0}), 1.4 + 0.25 + 0.6, 1e-6);
}

TEST(LinkSweep, NoCentreMovesFartherThanItsBoundAlongAStraightMotion) {
  // The chain with tilted axes and origins, so that no move is along a coordinate axis.
  RobotModel model = chain();
  model.links[1].origin.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()));
  model.links[2].origin.rotate(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(0, 1, 1).normalized()));
  model.links[3].origin.rotate(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 0, 1).normalized()));
  model.base = at(0.3, -0.2, 0.1);
  const LinkSweep sweep(model);
  std::mt19937_64 rng(3);
  const auto value = [&](const RobotModel::Joint& joint) {
    return std::uniform_real_distribution<double>(joint.lower, joint.upper)(rng);
  };
  constexpr int kStates = 9;
  double tightest = 0.0;  // the largest share of its bound a centre moved
  for (int motion = 0; motion < 500; ++motion) {
    std::vector<double> from, to, changes;
    for (const RobotModel::Joint& joint : model.joints) {
      from.push_back(value(joint));
      to.push_back(value(joint));
      changes.push_back(std::abs(to.back() - from.back()));
    }
    std::vector<std::vector<Eigen::Isometry3d>> poses;
    for (int k = 0; k < kStates; ++k) {
      std::vector<double> state(from.size());
      for (std::size_t j = 0; j < from.size(); ++j) {
        state[j] = from[j] + (to[j] - from[j]) * k / (kStates - 1);
      }
      poses.push_back(robot_link_poses(model, state));
    }
    for (std::size_t s = 0; s < model.spheres.size(); ++s) {
      const auto link = static_cast<std::size_t>(model.sphere_links[s]);
      const Eigen::Vector3d centre = model.spheres[s].center.cast<double>();
      for (int a = 0; a < kStates; ++a) {
        for (int b = a + 1; b < kStates; ++b) {
          std::vector<double> part(changes);
          for (double& change : part) change *= static_cast<double>(b - a) / (kStates - 1);
          const double moved = (poses[a][link] * centre - poses[b][link] * centre).norm();
          const double bound = sweep.along(link, part);
          ASSERT_LE(moved, bound + 1e-12) << "motion " << motion << ", sphere " << s;
          tightest = std::max(tightest, moved / bound);
        }
      }
    }
  }
  // Not slack everywhere: some centre moves nearly as far as its bound.
  EXPECT_GT(tightest, 0.9);
}

}  // namespace
}  // namespace sphys::test
