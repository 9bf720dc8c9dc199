#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "viewer/viewer.h"

namespace sphys::cli {

void add_view_command(CLI::App& app) {
  auto options = std::make_shared<viewer::ViewerOptions>();
  auto screenshot = std::make_shared<std::optional<std::string>>();
  auto no_cache = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "view", "Watch a scene live in a window (or render one frame of it to a PNG)");
  cmd->add_option("scene", options->scene, "Scene file (.json) or preset, e.g. stacks:4x50")
      ->required();
  cmd->add_option("--depth", options->depth, "Sphere-tree depth of every body (levels, 1..6)");
  cmd->add_option("--mode", options->mode, "Collision response: paper or plausible");
  cmd->add_option("--ground", options->ground, "octree or plane, instead of the scene's ground");
  cmd->add_option("--spheres", options->sphere_level,
                  "Draw each body's sphere-tree level N (1: the root; 0: none)")
      ->capture_default_str();
  cmd->add_option("--screenshot", *screenshot,
                  "Render one frame to this PNG and exit, after --frames physics frames");
  cmd->add_option("--frames", options->frames, "Physics frames before the screenshot")
      ->capture_default_str();
  cmd->add_option("--width", options->width, "Window width in pixels")->capture_default_str();
  cmd->add_option("--height", options->height, "Window height in pixels")->capture_default_str();
  cmd->add_flag("--no-cache", *no_cache, "Build sphere-trees even if they are cached");
  cmd->callback([options, screenshot, no_cache] {
    if (*screenshot) options->screenshot = **screenshot;
    options->use_cache = !*no_cache;
    viewer::run_viewer(*options);
  });
}

}  // namespace sphys::cli
