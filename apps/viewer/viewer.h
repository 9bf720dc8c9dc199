#pragma once

// `sphys view`: a window that runs a scene live at a fixed physics step and draws it at display
// rate, with an orbit camera, overlays and a panel; or, with `screenshot`, one frame to a PNG.

#include <filesystem>
#include <optional>
#include <string>

namespace sphys::viewer {

struct ViewerOptions {
  std::string scene;                  // a scene file or a preset
  std::optional<int> depth;           // sphere-tree depth of every body
  std::optional<std::string> mode;    // "paper" or "plausible"; unset: the scene's
  std::optional<std::string> ground;  // "octree" or "plane"; unset: the scene's
  int sphere_level = 0;               // sphere overlay: tree level drawn; 0: none
  std::optional<std::filesystem::path> screenshot;
  int frames = 0;  // physics frames before the screenshot
  int width = 1280;
  int height = 720;
  bool use_cache = true;  // the sphere-tree cache
};

// Returns when the window closes, or after the screenshot. Throws sphys::Error for bad input
// (the scene, the options) and std::runtime_error when no OpenGL 3.3 window can be made.
void run_viewer(const ViewerOptions& options);

}  // namespace sphys::viewer
