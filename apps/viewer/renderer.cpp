#include "renderer.h"

#include <epoxy/gl.h>
#include <stdexcept>

#include "camera.h"
#include "shader.h"

namespace sphys::viewer {
namespace {

constexpr const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  vec4 p = model * vec4(position, 1.0);
  world_position = p.xyz;
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * p;
}
)";

// Lambert from a sun high to one side, shadowed by a shadow map, plus an
// ambient term that is brighter for faces turned to the sky, so that the undersides of bodies
// read as such; far things fade into the haze.
constexpr const char* kMeshFragmentShader = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec3 color;
uniform float alpha;
uniform vec3 eye;
uniform vec3 to_sun;
uniform mat4 light_view_projection;
uniform sampler2DShadow shadow_map;
uniform float shadow_strength;
out vec4 fragment;
const vec3 kHaze = vec3(0.78, 0.82, 0.87);
float sunlit(vec3 n) {
  // Offset along the normal so that a surface does not shadow itself (acne).
  vec4 p = light_view_projection * vec4(world_position + 0.03 * n, 1.0);
  vec3 c = p.xyz / p.w * 0.5 + 0.5;
  if (any(lessThan(c, vec3(0.0))) || any(greaterThan(c, vec3(1.0)))) return 1.0;
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  // Four taps half a texel apart, each filtered 2 × 2 by the hardware comparison.
  float sum = 0.0;
  for (int x = 0; x < 2; ++x) {
    for (int y = 0; y < 2; ++y) {
      sum += texture(shadow_map, vec3(c.xy + (vec2(x, y) - 0.5) * texel, c.z - 0.001));
    }
  }
  return sum / 4.0;
}
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  float sun = max(dot(n, to_sun), 0.0);
  if (sun > 0.0 && shadow_strength > 0.0) sun *= mix(1.0, sunlit(n), shadow_strength);
  float sky = 0.5 + 0.5 * n.y;
  vec3 lit = color * (0.18 + 0.32 * sky + 0.62 * sun);
  float haze = clamp(length(world_position - eye) / 250.0, 0.0, 0.7);
  fragment = vec4(mix(lit, kHaze, haze), alpha);
}
)";

// The shadow map's pass: depth from the sun only.
constexpr const char* kDepthVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 model;
uniform mat4 light_view_projection;
void main() { gl_Position = light_view_projection * model * vec4(position, 1.0); }
)";

constexpr const char* kDepthFragmentShader = R"(#version 330 core
void main() {}
)";

constexpr int kShadowMapSize = 1024;  // unit: texels per side

// An orthographic view from the sun of the sphere (`center`, `radius`).
Eigen::Matrix4f sun_view_projection(const Eigen::Vector3f& to_sun, const Eigen::Vector3f& center,
                                    float radius) {
  const Eigen::Matrix4f view = look_at(center + 2.0f * radius * to_sun, -to_sun);
  // Depth from radius to 3 radius in front of the sun's eye maps to -1 .. 1.
  Eigen::Matrix4f ortho = Eigen::Matrix4f::Identity();
  ortho(0, 0) = 1.0f / radius;
  ortho(1, 1) = 1.0f / radius;
  ortho(2, 2) = -1.0f / radius;
  ortho(2, 3) = -2.0f;
  return ortho * view;
}

}  // namespace

Renderer::Renderer() {
  program_ = link_program(kMeshVertexShader, kMeshFragmentShader);
  model_location_ = glGetUniformLocation(program_, "model");
  view_projection_location_ = glGetUniformLocation(program_, "view_projection");
  color_location_ = glGetUniformLocation(program_, "color");
  alpha_location_ = glGetUniformLocation(program_, "alpha");
  eye_location_ = glGetUniformLocation(program_, "eye");
  light_location_ = glGetUniformLocation(program_, "light_view_projection");
  shadow_strength_location_ = glGetUniformLocation(program_, "shadow_strength");
  glUseProgram(program_);
  glUniform3fv(glGetUniformLocation(program_, "to_sun"), 1, kToSun.data());
  glUniform1i(glGetUniformLocation(program_, "shadow_map"), 0);

  depth_program_ = link_program(kDepthVertexShader, kDepthFragmentShader);
  depth_model_location_ = glGetUniformLocation(depth_program_, "model");
  depth_light_location_ = glGetUniformLocation(depth_program_, "light_view_projection");
  glGenTextures(1, &shadow_texture_);
  glBindTexture(GL_TEXTURE_2D, shadow_texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0,
               GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glGenFramebuffers(1, &shadow_framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_framebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) throw std::runtime_error("the shadow map's framebuffer is not complete");
}

void Renderer::begin_shadows(const Eigen::Vector3f& center, float radius) {
  light_view_projection_ = sun_view_projection(kToSun, center, radius);
  glGetIntegerv(GL_VIEWPORT, saved_viewport_.data());
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_framebuffer_);
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glUseProgram(depth_program_);
  glUniformMatrix4fv(depth_light_location_, 1, GL_FALSE, light_view_projection_.data());
}

void Renderer::cast_shadow(std::uint32_t mesh, const Eigen::Matrix4f& model) {
  const Mesh& gl_mesh = meshes_.at(mesh);
  glUniformMatrix4fv(depth_model_location_, 1, GL_FALSE, model.data());
  glBindVertexArray(gl_mesh.vertex_array);
  glDrawElements(GL_TRIANGLES, gl_mesh.index_count, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

void Renderer::end_shadows() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(saved_viewport_[0], saved_viewport_[1], saved_viewport_[2], saved_viewport_[3]);
  shadows_ = true;
}

Renderer::~Renderer() {
  clear_meshes();
  glDeleteFramebuffers(1, &shadow_framebuffer_);
  glDeleteTextures(1, &shadow_texture_);
  glDeleteProgram(depth_program_);
  glDeleteProgram(program_);
}

void Renderer::clear_meshes() {
  for (const Mesh& mesh : meshes_) {
    glDeleteVertexArrays(1, &mesh.vertex_array);
    glDeleteBuffers(1, &mesh.vertex_buffer);
    glDeleteBuffers(1, &mesh.index_buffer);
  }
  meshes_.clear();
}

std::uint32_t Renderer::add_mesh(const tools::TriangleMesh& mesh) {
  const std::vector<tools::Vec3d> normals = tools::vertex_normals(mesh);
  std::vector<float> vertices;  // position, normal
  vertices.reserve(mesh.vertices.size() * 6);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int c = 0; c < 3; ++c) vertices.push_back(static_cast<float>(mesh.vertices[v][c]));
    for (int c = 0; c < 3; ++c) vertices.push_back(static_cast<float>(normals[v][c]));
  }
  Mesh gl_mesh;
  gl_mesh.index_count = static_cast<int>(mesh.triangles.size() * 3);
  glGenVertexArrays(1, &gl_mesh.vertex_array);
  glBindVertexArray(gl_mesh.vertex_array);
  glGenBuffers(1, &gl_mesh.vertex_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, gl_mesh.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &gl_mesh.index_buffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_mesh.index_buffer);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(tools::Triangle)),
               mesh.triangles.data(), GL_STATIC_DRAW);
  constexpr GLsizei kStride = 6 * sizeof(float);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kStride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kStride,
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glBindVertexArray(0);
  meshes_.push_back(gl_mesh);
  return static_cast<std::uint32_t>(meshes_.size() - 1);
}

void Renderer::begin(const Eigen::Matrix4f& view, const Eigen::Matrix4f& projection,
                     const Eigen::Vector3f& eye) {
  glClearColor(0.78f, 0.82f, 0.87f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glUseProgram(program_);
  const Eigen::Matrix4f view_projection = projection * view;
  glUniformMatrix4fv(view_projection_location_, 1, GL_FALSE, view_projection.data());
  glUniform3fv(eye_location_, 1, eye.data());
  glUniformMatrix4fv(light_location_, 1, GL_FALSE, light_view_projection_.data());
  glUniform1f(shadow_strength_location_, shadows_ ? 1.0f : 0.0f);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, shadow_texture_);
  shadows_ = false;  // a frame without a shadow pass has no shadows
}

void Renderer::draw(std::uint32_t mesh, const Eigen::Matrix4f& model, const Eigen::Vector3f& color,
                    float alpha) {
  const Mesh& gl_mesh = meshes_.at(mesh);
  glUseProgram(program_);  // the overlays' lines may have drawn in between
  glUniformMatrix4fv(model_location_, 1, GL_FALSE, model.data());
  glUniform3fv(color_location_, 1, color.data());
  glUniform1f(alpha_location_, alpha);
  // See-through surfaces do not hide what is drawn after them.
  glDepthMask(alpha < 1.0f ? GL_FALSE : GL_TRUE);
  glBindVertexArray(gl_mesh.vertex_array);
  glDrawElements(GL_TRIANGLES, gl_mesh.index_count, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
}

}  // namespace sphys::viewer
