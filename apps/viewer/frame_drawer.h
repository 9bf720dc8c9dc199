#pragma once

// Frames of a running simulation drawn offscreen (a hidden window; under Xvfb where there is no
// display) and saved as PNGs: `sphys experiment`'s Figure 2 and its --render frames.

#include <filesystem>
#include <vector>

#include "body_view.h"
#include "camera.h"
#include "lines.h"
#include "renderer.h"
#include "scene_drawer.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scene.h"
#include "window.h"

namespace sphys::viewer {

class FrameDrawer {
 public:
  // The scene and its set-up world must outlive the drawer. The first frame is seen from far
  // enough to hold the bodies where they start, tall stacks included; later frames from the
  // viewer's usual camera on the ground, where they land. Throws std::runtime_error when no
  // OpenGL 3.3 window can be made (no display).
  FrameDrawer(const tools::Scene& scene, const tools::SimulationSetup& setup, int width,
              int height);

  // Draws the world's bodies where they are now; `first` for the frame before the first step.
  void draw(bool first);
  // Writes the frame drawn last, whole or not at all.
  void save(const std::filesystem::path& png) const;

 private:
  const tools::SimulationSetup* setup_;
  Window window_;
  Renderer renderer_;
  LineRenderer lines_;
  SceneDrawer drawer_;
  OrbitCamera start_camera_;
  OrbitCamera ground_camera_;
  std::vector<BodyView> bodies_;
};

}  // namespace sphys::viewer
