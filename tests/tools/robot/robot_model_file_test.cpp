// A RobotModel from the test robot's files: its joints in the chain's order with the URDF's
// limits, the SRDF's disabled pairs, kinematics that agree with tools::link_poses, and the files
// it refuses.

#include "sphys/tools/robot_model_file.h"

#include <fstream>
#include <map>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/spherize.h"
#include "support/query_worlds.h"
#include "support/temp_file.h"
#include "support/test_robot.h"

namespace sphys::tools {
namespace {

using testing::HasSubstr;

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The test robot written out, with spheres in cuRobo's YAML and an SRDF disabling two pairs (one
// naming a link the robot lacks).
struct Files {
  Files() {
    robot = test::write_test_robot(dir.path(), test::standard_test_robot());
    package = parse_robot_package(robot.package_option);
    const Robot loaded = load_robot(robot.urdf, std::span(&package, 1));
    SpherizeOptions options;
    options.total_spheres = 30;
    spheres = dir.path() / "spheres.yml";
    write_robot_spheres(spheres, SphereFileFormat::Curobo, loaded, spherize(loaded, options));
    srdf = dir.path() / "robot.srdf";
    write(
        srdf,
        "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n"
        "  <disable_collisions link1=\"base_link\" link2=\"shoulder_link\" reason=\"Adjacent\"/>\n"
        "  <disable_collisions link1=\"hand_link\" link2=\"no_such_link\" reason=\"Never\"/>\n"
        "</robot>\n");
  }
  test::TempDir dir;
  test::TestRobot robot;
  RobotPackage package;
  std::filesystem::path spheres;
  std::filesystem::path srdf;
};

// Made once for the suite: spherizing the robot takes seconds.
const Files& files_once() {
  static const Files files;
  return files;
}

TEST(RobotModelFile, TheTestRobotsChainLimitsSpheresAndDisabledPairs) {
  const Files& files = files_once();
  const RobotModel model =
      load_robot_model(files.robot.urdf, files.spheres, std::span(&files.package, 1), files.srdf);
  // The moving joints from the base out (the hand's children by name), with the URDF's limits.
  const test::RobotSpec spec = test::standard_test_robot();
  std::vector<std::string> expected;
  for (const test::RobotJointSpec& joint : spec.joints) {
    if (joint.type == "fixed") continue;
    expected.push_back(joint.name);
    const auto found = std::ranges::find_if(
        model.joints, [&](const RobotModel::Joint& j) { return j.name == joint.name; });
    ASSERT_NE(found, model.joints.end()) << joint.name;
    EXPECT_EQ(found->lower, joint.lower) << joint.name;
    EXPECT_EQ(found->upper, joint.upper) << joint.name;
  }
  std::vector<std::string> names;
  for (const RobotModel::Joint& joint : model.joints) names.push_back(joint.name);
  EXPECT_EQ(names, expected);
  EXPECT_EQ(model.links.size(), files.robot.links.size());
  EXPECT_EQ(model.links[0].name, "base_link");
  EXPECT_EQ(model.spheres.size(), model.sphere_links.size());
  EXPECT_GE(model.spheres.size(), files.robot.links_with_geometry.size());
  // The pair naming a link the robot lacks disables nothing.
  ASSERT_EQ(model.allowed_link_pairs.size(), 1u);
  EXPECT_EQ(model.allowed_link_pairs[0][0], model.link_index("base_link"));
  EXPECT_EQ(model.allowed_link_pairs[0][1], model.link_index("shoulder_link"));
}

TEST(RobotModelFile, KinematicsAgreeWithTheUrdfsLinkPoses) {
  const Files& files = files_once();
  const Robot robot = load_robot(files.robot.urdf, std::span(&files.package, 1));
  const RobotModel model =
      load_robot_model(files.robot.urdf, files.spheres, std::span(&files.package, 1));
  std::mt19937 rng(4);
  for (int n = 0; n < 50; ++n) {
    std::vector<double> values;
    std::map<std::string, double> named;
    for (const RobotModel::Joint& joint : model.joints) {
      values.push_back(std::uniform_real_distribution<double>(joint.lower, joint.upper)(rng));
      named[joint.name] = values.back();
    }
    const std::vector<Eigen::Isometry3d> ours = robot_link_poses(model, values);
    const std::map<std::string, Pose3d> theirs = link_poses(robot, named);
    for (std::size_t l = 0; l < model.links.size(); ++l) {
      const Pose3d& pose = theirs.at(model.links[l].name);
      EXPECT_LT((ours[l].matrix() - pose.matrix()).cwiseAbs().maxCoeff(), 1e-12)
          << model.links[l].name;
    }
  }
}

TEST(RobotModelFile, MimicJointsAndBrokenSrdfsAreRefusedNamingThem) {
  const Files& files = files_once();
  // The elbow mimics the shoulder's lift.
  std::string urdf;
  {
    std::ifstream in(files.robot.urdf);
    urdf.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::size_t elbow = urdf.find("<joint name=\"elbow\"");
  ASSERT_NE(elbow, std::string::npos);
  urdf.insert(urdf.find("</joint>", elbow), "<mimic joint=\"shoulder_lift\"/>");
  const std::filesystem::path mimic = files.robot.urdf.parent_path() / "mimic.urdf";
  write(mimic, urdf);
  EXPECT_THAT(test::error_message([&] {
                (void)load_robot_model(mimic, files.spheres, std::span(&files.package, 1));
              }),
              AllOf(HasSubstr("mimic.urdf"), HasSubstr("\"elbow\" mimics \"shoulder_lift\"")));
  const std::filesystem::path broken = files.dir.path() / "broken.srdf";
  write(broken, "<robot>\n\n  <disable_collisions link1=\"base_link\"/>\n</robot>\n");
  EXPECT_THAT(test::error_message([&] { (void)read_disabled_collisions(broken); }),
              AllOf(HasSubstr("broken.srdf"), HasSubstr("3"), HasSubstr("link2")));
  write(broken, "<robot><disable_collisions");
  EXPECT_THAT(test::error_message([&] { (void)read_disabled_collisions(broken); }),
              AllOf(HasSubstr("broken.srdf"), HasSubstr("not valid XML")));
}

}  // namespace
}  // namespace sphys::tools
