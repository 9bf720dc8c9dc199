#pragma once

// Draws unlit coloured line segments with OpenGL 3.3 core, for the overlays (contacts, normals,
// broad-phase boxes). Needs a current context (GLFW + libepoxy).

#include <span>

#include <Eigen/Core>

namespace sphys::viewer {

class LineRenderer {
 public:
  LineRenderer();
  ~LineRenderer();
  LineRenderer(const LineRenderer&) = delete;
  LineRenderer& operator=(const LineRenderer&) = delete;

  // Sets the camera for the draws that follow.
  void begin(const Eigen::Matrix4f& view_projection);
  // Segments from points[2i] to points[2i + 1]. `on_top` draws them over everything, so that
  // contacts inside a pile show; otherwise nearer surfaces hide them.
  void draw(std::span<const Eigen::Vector3f> points, const Eigen::Vector3f& color, bool on_top);

 private:
  unsigned program_ = 0;
  int view_projection_location_ = -1;
  int color_location_ = -1;
  unsigned vertex_array_ = 0;
  unsigned vertex_buffer_ = 0;
};

}  // namespace sphys::viewer
