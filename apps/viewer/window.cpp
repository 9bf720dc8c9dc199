#include "window.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <stb_image_write.h>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera.h"
#include "sphys/error.h"
#include "sphys/tools/text_file.h"

namespace sphys::viewer {

namespace {

constexpr int kDefaultSamples = 4;

bool software_renderer() {
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (name == nullptr) return false;
  const std::string renderer(name);
  return renderer.find("llvmpipe") != std::string::npos ||
         renderer.find("softpipe") != std::string::npos ||
         renderer.find("swrast") != std::string::npos;
}

}  // namespace

Window::Window(int width, int height, std::optional<int> samples, bool visible) {
  if (glfwInit() == GLFW_FALSE) throw std::runtime_error("cannot start GLFW (is there a display?)");
  open(width, height, samples.value_or(kDefaultSamples), visible);
  if (!samples && software_renderer()) {
    glfwDestroyWindow(handle_);
    open(width, height, 0, visible);
  }
}

void Window::open(int width, int height, int samples, bool visible) {
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, samples);
  handle_ = glfwCreateWindow(width, height, "sphys", nullptr, nullptr);
  if (handle_ == nullptr) {
    glfwTerminate();
    throw std::runtime_error("cannot open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(handle_);
}

Window::~Window() {
  glfwDestroyWindow(handle_);
  glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(handle_) != GLFW_FALSE; }

int Window::width() const {
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(handle_, &width, &height);
  return width;
}

int Window::height() const {
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(handle_, &width, &height);
  return height;
}

float Window::aspect() const {
  return static_cast<float>(width()) / static_cast<float>(std::max(height(), 1));
}

Gui::Gui(const Window& window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

Gui::~Gui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void Gui::new_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Gui::render() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool Gui::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Gui::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

Input::Input(const Window& window) { glfwGetCursorPos(window.handle(), &x_, &y_); }

void Input::update(const Window& window, const Gui& gui, OrbitCamera& camera) {
  double x = 0.0;
  double y = 0.0;
  glfwGetCursorPos(window.handle(), &x, &y);
  const auto dx = static_cast<float>(x - x_);
  const auto dy = static_cast<float>(y - y_);
  x_ = x;
  y_ = y;
  if (!gui.wants_mouse()) {
    GLFWwindow* handle = window.handle();
    if (glfwGetMouseButton(handle, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) camera.turn(dx, dy);
    if (glfwGetMouseButton(handle, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
        glfwGetMouseButton(handle, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) {
      camera.pan(dx, dy, static_cast<float>(std::max(window.height(), 1)));
    }
    camera.zoom(ImGui::GetIO().MouseWheel);
  }
  for (const int key : {GLFW_KEY_SPACE, GLFW_KEY_B, GLFW_KEY_J, GLFW_KEY_N, GLFW_KEY_P, GLFW_KEY_R,
                        GLFW_KEY_LEFT, GLFW_KEY_RIGHT}) {
    const bool down = glfwGetKey(window.handle(), key) == GLFW_PRESS;
    const auto k = static_cast<std::size_t>(key);
    pressed_[k] = down && !down_[k] && !gui.wants_keyboard();
    down_[k] = down;
  }
}

bool Input::pressed(int key) const {
  return key >= 0 && key < kKeys && pressed_[static_cast<std::size_t>(key)];
}

void write_png(const std::filesystem::path& path, int width, int height) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  std::string png;
  stbi_flip_vertically_on_write(1);  // OpenGL's rows start at the bottom
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (stbi_write_png_to_func(append, &png, width, height, 3, pixels.data(), width * 3) == 0) {
    throw Error(path.string() + ": cannot encode the PNG");
  }
  tools::write_text_file(path, png);
}

void check_window_size(int width, int height) {
  if (width < 16 || height < 16 || width > 8192 || height > 8192) {
    throw Error("--width and --height must be between 16 and 8192");
  }
}

}  // namespace sphys::viewer
