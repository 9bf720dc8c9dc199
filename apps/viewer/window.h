#pragma once

// The window and what it talks to: GLFW with an OpenGL 3.3 core context, Dear ImGui on top, the
// mouse and keys, and reading the frame back into a PNG.

#include <array>
#include <filesystem>
#include <optional>

struct GLFWwindow;

namespace sphys::viewer {

struct OrbitCamera;

class Window {
 public:
  // `samples` per pixel for multisample antialiasing (0: none); unset: 4 on a GPU, none on a
  // software renderer (Mesa's llvmpipe draws 2 to 3 times faster without). Throws
  // std::runtime_error when GLFW cannot start or no OpenGL 3.3 core window can be made. A hidden
  // window draws offscreen (pictures of a run without a window popping up).
  Window(int width, int height, std::optional<int> samples, bool visible = true);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  [[nodiscard]] GLFWwindow* handle() const { return handle_; }
  [[nodiscard]] bool should_close() const;
  // The framebuffer's size in pixels.
  [[nodiscard]] int width() const;
  [[nodiscard]] int height() const;
  [[nodiscard]] float aspect() const;

 private:
  void open(int width, int height, int samples, bool visible);

  GLFWwindow* handle_ = nullptr;
};

// Dear ImGui's context and its GLFW and OpenGL 3 backends, for the life of the object.
class Gui {
 public:
  explicit Gui(const Window& window);
  ~Gui();
  Gui(const Gui&) = delete;
  Gui& operator=(const Gui&) = delete;

  void new_frame();
  void render();
  [[nodiscard]] bool wants_mouse() const;
  [[nodiscard]] bool wants_keyboard() const;
};

// The mouse moves the camera (left drag turns, right or middle drag pans, the wheel zooms);
// keys are reported once per press.
class Input {
 public:
  explicit Input(const Window& window);
  // Call once per displayed frame; the camera moves unless the panel has the mouse.
  void update(const Window& window, const Gui& gui, OrbitCamera& camera);
  // True on the frame a key (a GLFW_KEY_* code) went down while the panel did not want keys.
  [[nodiscard]] bool pressed(int key) const;
  [[nodiscard]] double x() const { return x_; }
  [[nodiscard]] double y() const { return y_; }

 private:
  static constexpr int kKeys = 512;
  double x_ = 0.0;
  double y_ = 0.0;
  std::array<bool, kKeys> down_{};
  std::array<bool, kKeys> pressed_{};
};

// Throws sphys::Error "--width and --height must be between 16 and 8192" for a window size the
// viewer does not open.
void check_window_size(int width, int height);

// Reads the back buffer (`width` × `height`) and writes it as a PNG, whole or not at all.
// Throws sphys::Error naming the file.
void write_png(const std::filesystem::path& path, int width, int height);

}  // namespace sphys::viewer
