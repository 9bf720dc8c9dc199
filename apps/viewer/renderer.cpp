#include "renderer.h"

#include <epoxy/gl.h>

#include "shader.h"

namespace sphys::viewer {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
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

// Lambert from a sun high to one side, plus an ambient term that is brighter for faces turned
// to the sky, so that the undersides of bodies read as such; far things fade into the haze.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec3 color;
uniform float alpha;
uniform vec3 eye;
out vec4 fragment;
const vec3 kToSun = normalize(vec3(0.45, 0.8, 0.35));
const vec3 kHaze = vec3(0.78, 0.82, 0.87);
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  float sun = max(dot(n, kToSun), 0.0);
  float sky = 0.5 + 0.5 * n.y;
  vec3 lit = color * (0.18 + 0.32 * sky + 0.62 * sun);
  float haze = clamp(length(world_position - eye) / 250.0, 0.0, 0.7);
  fragment = vec4(mix(lit, kHaze, haze), alpha);
}
)";

}  // namespace

Renderer::Renderer() {
  program_ = link_program(kVertexShader, kFragmentShader);
  model_location_ = glGetUniformLocation(program_, "model");
  view_projection_location_ = glGetUniformLocation(program_, "view_projection");
  color_location_ = glGetUniformLocation(program_, "color");
  alpha_location_ = glGetUniformLocation(program_, "alpha");
  eye_location_ = glGetUniformLocation(program_, "eye");
}

Renderer::~Renderer() {
  clear_meshes();
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
