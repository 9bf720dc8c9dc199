// A scene with the test robot run by `sphys simulate`: its links recorded as bodies, where the
// world has them, with its joints; and drawn by `sphys view`, live and replayed alike, with their
// spheres and joints.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "apps/cli.h"
#include "sphys/robot_model.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"
#include "sphys/world.h"
#include "support/screenshot.h"
#include "support/temp_file.h"
#include "support/test_robot_scene.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;

// The robot starts limp at every joint's 0 and is driven to these.
constexpr const char* kTargets = R"("targets": [0.3, 0.5, 0.4, 0.015, 0.015])";
// A small bunny falling beside it, at 1 kHz control.
constexpr const char* kBunnyAt1kHz =
    R"("time_step": 0.001, "bodies": [{"size": 0.2, "position": [-0.6, 0.3, 0.4],
       "sphere_tree": {"method": "octree", "depth": 1}}])";
constexpr int kFrames = 300;

Eigen::Isometry3d isometry(const Vec3& position, const Quat& orientation) {
  return Eigen::Translation3d(position.cast<double>()) * orientation.cast<double>();
}

// The link of each robot body (World::robot_bodies): the root's, then each joint's.
std::vector<std::size_t> body_links(const RobotModel& model) {
  std::vector<std::size_t> links(model.joints.size() + 1, 0);
  for (std::size_t l = 1; l < model.links.size(); ++l) {
    if (model.links[l].joint >= 0) links[static_cast<std::size_t>(model.links[l].joint) + 1] = l;
  }
  return links;
}

TEST(RobotSceneRecording, SimulateRecordsTheLinksWhereTheWorldHasThem) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path scene_path =
      dir.write("scene.json", test::scene_with_test_robot(dir.path(), kTargets, kBunnyAt1kHz));
  const fs::path out = dir.path() / "run";
  const test::CommandResult run = test::sphys_cli({"simulate", scene_path.string(), "--frames",
                                                   std::to_string(kFrames), "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const tools::Recording recording = tools::read_recording(out / "recording.sphysrec");

  // The same run here, which steps the same bits.
  const tools::Scene scene = tools::read_scene_file(scene_path);
  const tools::SimulationSetup setup = tools::build_world(scene);
  const tools::SceneRobots robots = tools::add_scene_robots(scene, *setup.world);
  World& world = *setup.world;
  ASSERT_EQ(robots.robots.size(), 1U);
  const RobotId robot = robots.robots[0];
  // The bunny, then the robot's root and the links of its 5 moving joints.
  ASSERT_EQ(recording.body_count, 7U);
  ASSERT_EQ(recording.frame_count, static_cast<std::uint32_t>(kFrames + 1));
  ASSERT_EQ(recording.joints.size(), 5U);
  EXPECT_EQ(recording.joints, tools::recorded_joints(scene, robots));
  for (const tools::RecordedJoint& joint : recording.joints) {
    ASSERT_TRUE(joint.body_a && joint.body_b);  // the root is a body too, a static one
    EXPECT_GE(*joint.body_a, 1U);               // after the bunny
    EXPECT_GE(*joint.body_b, 1U);
  }

  // Each link's pose in its body's frame, fixed while the robot moves.
  const std::vector<std::size_t> links = body_links(world.robot_model(robot));
  const std::vector<Eigen::Isometry3d> start = world.robot_link_poses_in_world(robot);
  std::vector<Eigen::Isometry3d> link_in_body;
  for (std::size_t b = 0; b < robots.bodies.size(); ++b) {
    const Transform& pose = world.body(robots.bodies[b]).pose;
    link_in_body.push_back(isometry(pose.translation, pose.rotation).inverse() * start[links[b]]);
  }
  const auto expect_links_recorded = [&](int frame) {
    const std::vector<Eigen::Isometry3d> now = world.robot_link_poses_in_world(robot);
    const std::span<const tools::BodyPose> poses =
        recording.frame(static_cast<std::uint32_t>(frame));
    for (std::size_t b = 0; b < robots.bodies.size(); ++b) {
      const tools::BodyPose& recorded = poses[1 + b];
      const Eigen::Isometry3d link =
          isometry(recorded.position, recorded.orientation) * link_in_body[b];
      const Eigen::Isometry3d& truth = now[links[b]];
      EXPECT_LT((link.translation() - truth.translation()).norm(), 1e-5)
          << "frame " << frame << ", body " << b;
      const Eigen::Matrix3d turn = link.rotation().transpose() * truth.rotation();
      EXPECT_LT(Eigen::AngleAxisd(turn).angle(), 1e-5) << "frame " << frame << ", body " << b;
    }
  };
  expect_links_recorded(0);
  for (int frame = 1; frame <= kFrames; ++frame) world.step(static_cast<float>(scene.time_step));
  expect_links_recorded(kFrames);

  // The arm moved, and its hinges held: each one's two anchors, placed by the recorded poses of
  // the bodies the recorded joint names, meet.
  const std::span<const tools::BodyPose> last =
      recording.frame(static_cast<std::uint32_t>(kFrames));
  EXPECT_GT((last[6].position - recording.frame(0)[6].position).norm(), 0.02F);
  int hinges = 0;
  for (const tools::RecordedJoint& joint : recording.joints) {
    if (joint.type != JointType::kHinge) continue;
    ++hinges;
    const tools::BodyPose& a = last[*joint.body_a];
    const tools::BodyPose& b = last[*joint.body_b];
    const Vec3 on_a = a.orientation * joint.anchor_a + a.position;
    const Vec3 on_b = b.orientation * joint.anchor_b + b.position;
    EXPECT_LT((on_a - on_b).norm(), 1e-3F);
  }
  EXPECT_EQ(hinges, 3);

  // The export animates them too: the bunny's mesh and one per robot body.
  const test::CommandResult exported =
      test::sphys_cli({"export", (out / "recording.sphysrec").string(), "--gltf",
                       (dir.path() / "run.glb").string()});
  ASSERT_EQ(exported.exit_code, 0) << exported.out << exported.err;
  EXPECT_THAT(exported.out, testing::HasSubstr("7 bodies (7 distinct meshes)"));
}

constexpr int kShotWidth = 320;
constexpr int kShotHeight = 180;

// The robot's links are drawn in the bodies' sand colour, found nowhere else in a scene without
// bodies (sky, grey ground, blue spheres, magenta joints).
bool sand(int r, int g, int b) { return r > b + 40 && g > b + 10; }
bool magenta(int r, int g, int b) { return r > 180 && g < 90 && b > 180; }

TEST(RobotSceneRecording, TheViewerDrawsTheRobotLiveAndReplayedWithItsSpheresAndJoints) {
  const test::TempDir dir;
  const fs::path scene_path = dir.write(
      "scene.json",
      test::scene_with_test_robot(dir.path(), kTargets, R"("time_step": 0.001, "bodies": [])"));
  const fs::path out = dir.path() / "run";
  const test::CommandResult run =
      test::sphys_cli({"simulate", scene_path.string(), "--frames", "200", "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const std::string recording = (out / "recording.sphysrec").string();
  const auto shot = [&](const std::string& name, std::vector<std::string> args) {
    return test::screenshot(dir.path() / (name + ".png"), std::move(args), kShotWidth, kShotHeight);
  };
  const test::Image live = shot("live", {scene_path.string(), "--frames", "200"});
  const test::Image replay = shot("replay", {"--replay", recording, "--frames", "200"});
  EXPECT_EQ(live.rgb, replay.rgb);
  const int links = test::count_pixels(replay, sand);
  EXPECT_GT(links, 300);

  // The spheres' overlay tints the links blue; the joints' overlay is drawn over them.
  const test::Image spheres =
      shot("spheres", {"--replay", recording, "--frames", "200", "--spheres", "1"});
  EXPECT_LT(test::count_pixels(spheres, sand), links / 2);
  const test::Image hidden =
      shot("hidden", {"--replay", recording, "--frames", "200", "--no-joints"});
  EXPECT_GT(test::count_pixels(replay, magenta), 10);
  EXPECT_EQ(test::count_pixels(hidden, magenta), 0);

  // A recording made before robots were recorded keeps the scene's bodies alone (none here): it
  // still replays, without the robot.
  const fs::path old = dir.path() / "old.sphysrec";
  {
    tools::RecordingWriter writer(old, 0, 0.001, tools::read_recording(recording).metadata);
    writer.add_frame({});
    writer.finish();
  }
  const test::Image without = shot("old", {"--replay", old.string()});
  EXPECT_EQ(test::count_pixels(without, sand), 0);
}

}  // namespace
}  // namespace sphys
