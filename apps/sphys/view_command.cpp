#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "joint_option.h"
#include "sphys/tools/robot.h"
#include "sphys/tools/scene.h"
#include "viewer/robot_view.h"
#include "viewer/viewer.h"

namespace sphys::cli {
namespace {

struct ViewArguments {
  std::optional<std::string> scene;
  std::optional<std::string> replay;
  std::optional<std::string> mode;
  std::optional<std::string> ground;
  std::optional<std::string> screenshot;
  bool no_cache = false;
  bool no_shadows = false;
  bool no_joints = false;  // --no-joints, of a scene's joints (not a robot's --joint)
  // A robot (the scene argument is a .urdf file).
  std::vector<std::string> packages;
  std::optional<std::string> spheres_from;
  std::vector<std::string> joints;
};

bool is_urdf(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".urdf" || extension == ".URDF";
}

// `sphys view ROBOT.urdf`: the robot's links and their spheres.
void view_robot(const viewer::ViewerOptions& options, const ViewArguments& args) {
  viewer::RobotViewOptions robot;
  robot.urdf = *args.scene;
  for (const std::string& package : args.packages) {
    robot.packages.push_back(tools::parse_robot_package(package));
  }
  if (args.spheres_from) robot.spheres_from = *args.spheres_from;
  for (const std::string& joint : args.joints) robot.joints.insert(parse_joint("--joint", joint));
  robot.screenshot = options.screenshot;
  robot.width = options.width;
  robot.height = options.height;
  robot.msaa = options.msaa;
  robot.shadows = options.shadows;
  viewer::run_robot_viewer(robot);
}

}  // namespace

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<viewer::ViewerOptions>();
  auto args = std::make_shared<ViewArguments>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Watch a scene live or replay a recording in a window (or render a frame to a PNG)");
  cmd->add_option(
         "scene", args->scene,
         std::string("Scene file (.json), preset (e.g. stacks:4x50) or robot (.urdf); default ") +
             viewer::kDefaultScene)
      ->check(kFileName);
  cmd->add_option("--replay", args->replay,
                  "Play back a recording of sphys simulate (recording.sphysrec) instead")
      ->check(kFileName);
  cmd->add_option("--depth", options->depth, "Sphere-tree depth of every body (levels, 1..6)");
  cmd->add_option("--mode", args->mode, setting_help("response") + " Replaces the scene's value.");
  cmd->add_option("--ground", args->ground, "octree or plane, instead of the scene's ground");
  cmd->add_option("--spheres", options->sphere_level,
                  "Draw each body's sphere-tree level N (1: the root; 0: none)")
      ->capture_default_str();
  cmd->add_flag("--show-contacts", options->show_contacts, "Draw contact points and normals");
  cmd->add_flag("--show-boxes", options->show_boxes, "Draw the broad phase's boxes");
  cmd->add_flag("--no-joints", args->no_joints,
                "Draw no joints (by default each is drawn over the bodies; key J toggles it)");
  cmd->add_flag("--no-shadows", args->no_shadows, "Draw without the sun's shadows (faster)");
  cmd->add_option("--screenshot", args->screenshot,
                  "Render one frame to this PNG and exit, after --frames physics frames (with "
                  "--replay: the recording's frame --frames)")
      ->check(kFileName);
  cmd->add_option("--frames", options->frames,
                  "Physics frames before the screenshot; with --replay, the frame to start at")
      ->capture_default_str();
  cmd->add_option("--exit-after", options->exit_after,
                  "Close the window after N displayed frames and print the frame rate");
  cmd->add_option("--width", options->width, "Window width in pixels")->capture_default_str();
  cmd->add_option("--height", options->height, "Window height in pixels")->capture_default_str();
  cmd->add_option("--msaa", options->msaa,
                  "Antialiasing samples per pixel (0: off); default 4, none on software OpenGL");
  cmd->add_flag("--no-cache", args->no_cache, "Build sphere-trees even if they are cached");
  cmd->add_option("--spheres-from", args->spheres_from,
                  "With a robot (.urdf): draw the spheres of this file of sphys spherize")
      ->check(kFileName);
  cmd->add_option("--joint", args->joints,
                  "With a robot: NAME=VALUE sets a joint (rad or m; others stand at 0)");
  cmd->add_option("--package", args->packages,
                  "With a robot: NAME=DIR, where package://NAME/ mesh paths point");
  cmd->callback([options, args] {
    if (args->scene && is_urdf(*args->scene)) {
      if (args->replay || args->mode || args->ground || options->sphere_level != 0) {
        throw Error(
            "--replay, --mode, --ground and --spheres are for scenes; a robot takes "
            "--spheres-from, --joint and --package");
      }
      if (args->screenshot) options->screenshot = *args->screenshot;
      options->shadows = !args->no_shadows;
      view_robot(*options, *args);
      return;
    }
    if (args->spheres_from || !args->joints.empty() || !args->packages.empty()) {
      throw Error("--spheres-from, --joint and --package are for a robot (.urdf)");
    }
    if (args->replay) {
      if (args->scene) throw Error("give a scene or --replay, not both");
      if (args->mode || args->ground) {
        throw Error("--mode and --ground change a live run; a replay shows what was recorded");
      }
      options->replay = *args->replay;
    }
    if (args->scene) options->scene = *args->scene;
    if (args->mode) options->mode = parse_option("--mode", *args->mode, tools::parse_response_mode);
    if (args->ground) options->ground = tools::parse_ground_option(*args->ground);
    if (args->screenshot) options->screenshot = *args->screenshot;
    options->use_cache = !args->no_cache;
    options->shadows = !args->no_shadows;
    options->show_joints = !args->no_joints;
    viewer::run_viewer(*options);
  });
}

}  // namespace sphys::cli
