#pragma once

// Compiles and links a GLSL program; needs a current OpenGL context.

namespace sphys::viewer {

// Throws std::runtime_error with the driver's log when a shader does not compile or link.
unsigned link_program(const char* vertex_source, const char* fragment_source);

}  // namespace sphys::viewer
