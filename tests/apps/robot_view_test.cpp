// `sphys view ROBOT.urdf`: the test robot's links drawn at a pose, its spheres see-through over
// them, to a PNG under Xvfb.

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/screenshot.h"
#include "support/temp_file.h"
#include "support/test_robot.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320;
constexpr int kHeight = 200;

// The robot and its spheres are made once for the suite.
class RobotView : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    robot_ = new test::TestRobot(test::write_test_robot(dir_->path(), test::standard_test_robot()));
    spheres_ = dir_->path() / "spheres.yml";
    const test::CommandResult r =
        test::sphys_cli({"spherize", robot_->urdf.string(), "--package", robot_->package_option,
                         "--spheres", "20", "--format", "curobo", "-o", spheres_.string()});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  static void TearDownTestSuite() {
    delete robot_;
    delete dir_;
  }

  // A screenshot of the robot with these further options.
  test::Image shot(const std::string& name, const std::vector<std::string>& options) {
    std::vector<std::string> args = {robot_->urdf.string(), "--package", robot_->package_option};
    args.insert(args.end(), options.begin(), options.end());
    return test::screenshot(dir_->path() / (name + ".png"), args, kWidth, kHeight);
  }

  static inline test::TempDir* dir_ = nullptr;
  static inline test::TestRobot* robot_ = nullptr;
  static inline fs::path spheres_;
};

// Pixels that differ between two pictures of the same size, and of those the ones that turned
// bluer (the spheres' colour).
struct Difference {
  int changed = 0;
  int bluer = 0;
};

Difference difference(const test::Image& before, const test::Image& after) {
  Difference d;
  for (std::size_t i = 0; i + 2 < before.rgb.size() && i + 2 < after.rgb.size(); i += 3) {
    if (before.rgb[i] == after.rgb[i] && before.rgb[i + 1] == after.rgb[i + 1] &&
        before.rgb[i + 2] == after.rgb[i + 2]) {
      continue;
    }
    ++d.changed;
    d.bluer += after.rgb[i + 2] - after.rgb[i] > before.rgb[i + 2] - before.rgb[i] ? 1 : 0;
  }
  return d;
}

TEST_F(RobotView, TheRobotFillsThePictureAndItsSpheresTintItBlue) {
  const test::Image plain = shot("plain", {});
  ASSERT_EQ(plain.width, kWidth);
  ASSERT_EQ(plain.height, kHeight);
  // The robot stands in the middle of the sky: corners sky, a good part of the picture not.
  EXPECT_TRUE(test::is_sky(plain.at(0, 0)));
  EXPECT_TRUE(test::is_sky(plain.at(kWidth - 1, kHeight - 1)));
  const int robot = test::count_pixels(plain, [](int r, int g, int b) {
    const unsigned char p[3] = {static_cast<unsigned char>(r), static_cast<unsigned char>(g),
                                static_cast<unsigned char>(b)};
    return !test::is_sky(p);
  });
  EXPECT_GT(robot, kWidth * kHeight / 20);

  const test::Image spheres = shot("spheres", {"--spheres-from", spheres_.string()});
  const Difference d = difference(plain, spheres);
  // The spheres cover every link and reach past it: many pixels change, most towards blue.
  EXPECT_GT(d.changed, robot / 2);
  EXPECT_GT(d.bluer, d.changed * 3 / 4);
}

TEST_F(RobotView, AJointMovesTheLinksBeyondIt) {
  const test::Image zero = shot("zero", {});
  const test::Image bent = shot("bent", {"--joint", "shoulder_lift=1.2", "--joint", "elbow=0.8"});
  EXPECT_GT(difference(zero, bent).changed, kWidth * kHeight / 50);
  // Back to zero by name: the same picture.
  const test::Image again = shot("again", {"--joint", "shoulder_lift=0"});
  EXPECT_EQ(zero.rgb, again.rgb);
}

TEST_F(RobotView, BadRobotOptionsExitWithCode2) {
  const std::vector<std::string> base = {"view", robot_->urdf.string(), "--package",
                                         robot_->package_option};
  const auto with = [&](const std::vector<std::string>& options) {
    std::vector<std::string> args = base;
    args.insert(args.end(), options.begin(), options.end());
    args.insert(args.end(), {"--screenshot", (dir_->path() / "bad.png").string()});
    return args;
  };
  test::expect_bad_input(with({"--joint", "no_such_joint=1"}), "no joint \"no_such_joint\"");
  test::expect_bad_input(with({"--joint", "wrist=1"}), "joint \"wrist\" is fixed");
  test::expect_bad_input(with({"--joint", "elbow=abc"}), "--joint: \"abc\" is not a number");
  test::expect_bad_input(with({"--joint", "elbow"}), "--joint: expected NAME=VALUE");
  test::expect_bad_input(with({"--spheres", "2"}), "a robot takes --spheres-from");
  // Spheres for a link the robot does not have.
  const fs::path foreign = dir_->path() / "foreign.yml";
  {
    std::ofstream out(foreign);
    out << "collision_spheres:\n  no_such_link:\n    - center: [0, 0, 0]\n      radius: 0.1\n";
  }
  test::expect_bad_input(with({"--spheres-from", foreign.string()}), "no_such_link");
  EXPECT_FALSE(fs::exists(dir_->path() / "bad.png"));
}

}  // namespace
}  // namespace sphys
