#pragma once

// `sphys view`: a window that runs a scene live at a fixed physics step and draws it at display
// rate, or plays a recording back, with an orbit camera, overlays and a panel; or, with
// `screenshot`, one frame to a PNG.

#include <filesystem>
#include <optional>
#include <string>

#include "sphys/tools/scene.h"

namespace sphys::viewer {

// The scene `sphys view` shows when given none: the paper's first layout.
inline constexpr const char* kDefaultScene = "stacks:4x25";

struct ViewerOptions {
  std::string scene = kDefaultScene;  // a scene file or a preset
  // A recording of `sphys simulate` to play back instead of running a scene.
  std::optional<std::filesystem::path> replay;
  std::optional<int> depth;                       // sphere-tree depth of every body
  std::optional<ResponseMode> mode;               // unset: the scene's
  std::optional<tools::GroundSpec::Kind> ground;  // unset: the scene's
  int sphere_level = 0;                           // sphere overlay: tree level drawn; 0: none
  bool show_contacts = false;
  bool show_boxes = false;
  bool show_joints = true;
  bool shadows = true;
  std::optional<std::filesystem::path> screenshot;
  // Physics frames before the screenshot; with a replay, the recording's frame shown.
  int frames = 0;
  // Closes the window after this many displayed frames and prints the display's frame rate.
  std::optional<int> exit_after;
  int width = 1280;
  int height = 720;
  // Samples per pixel for antialiasing; 0 turns it off; unset: 4 on a GPU, none on a software
  // renderer such as Mesa's llvmpipe under Xvfb.
  std::optional<int> msaa;
  bool use_cache = true;  // the sphere-tree cache
};

// Returns when the window closes, or after the screenshot. Throws sphys::Error for bad input
// (the scene, the recording, the options) and std::runtime_error when no OpenGL 3.3 window can
// be made.
void run_viewer(const ViewerOptions& options);

}  // namespace sphys::viewer
