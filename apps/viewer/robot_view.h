#pragma once

// `sphys view ROBOT.urdf`: a robot's links at a pose, with the spheres of `sphys spherize`
// see-through over them, to look at before a planner trusts them; or one frame to a PNG.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sphys/tools/robot.h"

namespace sphys::viewer {

struct RobotViewOptions {
  std::filesystem::path urdf;
  std::vector<tools::RobotPackage> packages;
  // A file written by `sphys spherize` (any of its formats): its spheres are drawn.
  std::optional<std::filesystem::path> spheres_from;
  std::map<std::string, double> joints;  // unit: rad or m; a joint not named stands at 0
  std::optional<std::filesystem::path> screenshot;
  int width = 1280;
  int height = 720;
  std::optional<int> msaa;  // as ViewerOptions::msaa
  bool shadows = true;
};

// Returns when the window closes, or after the screenshot. Throws sphys::Error for bad input
// (the URDF, its meshes, the spheres file, a joint) and std::runtime_error when no OpenGL 3.3
// window can be made.
void run_robot_viewer(const RobotViewOptions& options);

}  // namespace sphys::viewer
