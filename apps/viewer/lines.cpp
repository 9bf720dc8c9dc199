#include "lines.h"

#include <epoxy/gl.h>

#include "shader.h"

namespace sphys::viewer {
namespace {

constexpr const char* kLineVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * vec4(position, 1.0); }
)";

constexpr const char* kLineFragmentShader = R"(#version 330 core
uniform vec3 color;
out vec4 fragment;
void main() { fragment = vec4(color, 1.0); }
)";

}  // namespace

LineRenderer::LineRenderer() {
  program_ = link_program(kLineVertexShader, kLineFragmentShader);
  view_projection_location_ = glGetUniformLocation(program_, "view_projection");
  color_location_ = glGetUniformLocation(program_, "color");
  glGenVertexArrays(1, &vertex_array_);
  glBindVertexArray(vertex_array_);
  glGenBuffers(1, &vertex_buffer_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
  glBindVertexArray(0);
}

LineRenderer::~LineRenderer() {
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteBuffers(1, &vertex_buffer_);
  glDeleteProgram(program_);
}

void LineRenderer::begin(const Eigen::Matrix4f& view_projection) {
  glUseProgram(program_);
  glUniformMatrix4fv(view_projection_location_, 1, GL_FALSE, view_projection.data());
}

void LineRenderer::draw(std::span<const Eigen::Vector3f> points, const Eigen::Vector3f& color,
                        bool on_top) {
  if (points.size() < 2) return;
  glUseProgram(program_);
  glUniform3fv(color_location_, 1, color.data());
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  // Eigen::Vector3f is three packed floats, as the attribute reads them.
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(Eigen::Vector3f)),
               points.data(), GL_STREAM_DRAW);
  if (on_top) glDisable(GL_DEPTH_TEST);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(points.size() / 2 * 2));
  glEnable(GL_DEPTH_TEST);
  glBindVertexArray(0);
}

}  // namespace sphys::viewer
