#pragma once

// Draws triangle meshes with OpenGL 3.3 core: one shader with a sun casting shadows (a shadow
// map), a sky-and-ground ambient term and distance haze, opaque or see-through. Needs a current
// context (GLFW + libepoxy).

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::viewer {

// Where the sunlight comes from: high, to the left of the initial view, so that shadows fall
// to the right of what casts them. unit vector
inline const Eigen::Vector3f kToSun = Eigen::Vector3f(-0.45f, 0.8f, 0.3f).normalized();

class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads a mesh; the handle is what draw() takes.
  std::uint32_t add_mesh(const tools::TriangleMesh& mesh);
  // Frees every mesh, e.g. before the meshes of another scene; their handles become invalid.
  void clear_meshes();

  // The shadow pass, before begin(): the sun's view covers the sphere (`center`, `radius`, unit:
  // m); every mesh given to cast_shadow() shadows what begin() draws next. A frame without this
  // pass has no shadows.
  void begin_shadows(const Eigen::Vector3f& center, float radius);
  void cast_shadow(std::uint32_t mesh, const Eigen::Matrix4f& model);
  void end_shadows();

  // Clears the frame and sets the camera for the draws that follow.
  void begin(const Eigen::Matrix4f& view, const Eigen::Matrix4f& projection,
             const Eigen::Vector3f& eye);
  // `model` places the mesh in the world; alpha < 1 draws it see-through (draw those last).
  void draw(std::uint32_t mesh, const Eigen::Matrix4f& model, const Eigen::Vector3f& color,
            float alpha = 1.0f);

 private:
  struct Mesh {
    unsigned vertex_array = 0;
    unsigned vertex_buffer = 0;
    unsigned index_buffer = 0;
    int index_count = 0;
  };
  unsigned program_ = 0;
  int model_location_ = -1;
  int view_projection_location_ = -1;
  int color_location_ = -1;
  int alpha_location_ = -1;
  int eye_location_ = -1;
  int light_location_ = -1;
  int shadow_strength_location_ = -1;
  unsigned depth_program_ = 0;
  int depth_model_location_ = -1;
  int depth_light_location_ = -1;
  unsigned shadow_texture_ = 0;
  unsigned shadow_framebuffer_ = 0;
  Eigen::Matrix4f light_view_projection_ = Eigen::Matrix4f::Identity();
  std::array<int, 4> saved_viewport_{};
  bool shadows_ = false;
  std::vector<Mesh> meshes_;
};

}  // namespace sphys::viewer
