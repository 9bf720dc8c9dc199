#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "sphys/tools/scene.h"
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
};

}  // namespace

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<viewer::ViewerOptions>();
  auto args = std::make_shared<ViewArguments>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Watch a scene live or replay a recording in a window (or render a frame to a PNG)");
  cmd->add_option("scene", args->scene,
                  std::string("Scene file (.json) or preset, e.g. stacks:4x50; default ") +
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
  cmd->callback([options, args] {
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
    viewer::run_viewer(*options);
  });
}

}  // namespace sphys::cli
