#include "viewer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <imgui.h>
#include <memory>
#include <stb_image_write.h>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "camera.h"
#include "renderer.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/scene_meshes.h"
#include "sphys/tools/text_file.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::viewer {
namespace {

using Clock = std::chrono::steady_clock;

// The plane drawn for an infinite ground plane. unit: m
constexpr double kPlaneSize = 120.0;
// Physics steps one displayed frame may run at most, so that a slow step does not snowball.
constexpr int kMaxStepsPerFrame = 4;

const Eigen::Vector3f kBodyColour(0.86f, 0.72f, 0.52f);
const Eigen::Vector3f kAsleepColour(0.55f, 0.62f, 0.80f);
const Eigen::Vector3f kGroundColour(0.50f, 0.53f, 0.50f);
const Eigen::Vector3f kSphereColour(0.25f, 0.55f, 0.95f);
// The shadow under a body on the ground, and the height at which it has faded out. unit: m
constexpr float kShadowAlpha = 0.45f;
constexpr float kShadowFade = 12.0f;

Eigen::Matrix4f model_matrix(const Transform& pose, float scale = 1.0f) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 3>(0, 0) = pose.rotation.toRotationMatrix() * scale;
  m.block<3, 1>(0, 3) = pose.translation;
  return m;
}

tools::Scene load(const ViewerOptions& options) {
  tools::Scene scene = tools::load_scene(options.scene);
  if (options.mode) scene.response = tools::parse_response_mode(*options.mode);
  if (options.ground) scene.ground.kind = tools::parse_ground_option(*options.ground);
  if (options.depth) {
    for (tools::BodySpec& body : scene.bodies) {
      if (!body.tree.sph_file) body.tree.depth = *options.depth;
    }
  }
  return scene;
}

// The simulation the window shows: the scene's world, rebuilt on reset.
struct Simulation {
  tools::Scene scene;
  tools::BuildWorldOptions build;
  tools::SimulationSetup setup;
  int frame = 0;

  void reset() {
    setup = tools::build_world(scene, build);
    frame = 0;
  }
  const StepStats& step() {
    ++frame;
    return setup.world->step(static_cast<float>(scene.time_step));
  }
};

struct Window {
  GLFWwindow* handle = nullptr;
  Window(int width, int height) {
    if (glfwInit() == GLFW_FALSE)
      throw std::runtime_error("cannot start GLFW (is there a display?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 4);
    handle = glfwCreateWindow(width, height, "sphys", nullptr, nullptr);
    if (handle == nullptr) {
      glfwTerminate();
      throw std::runtime_error("cannot open an OpenGL 3.3 core window");
    }
    glfwMakeContextCurrent(handle);
  }
  ~Window() {
    glfwDestroyWindow(handle);
    glfwTerminate();
  }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
};

// Meshes on the GPU for a simulation's shapes, its ground and the overlay's sphere.
struct SceneGraphics {
  std::vector<std::uint32_t> shapes;
  std::optional<std::uint32_t> ground;
  std::uint32_t sphere = 0;

  SceneGraphics(Renderer& renderer, const Simulation& simulation) {
    for (const tools::BodyShape& shape : simulation.setup.shapes) {
      shapes.push_back(renderer.add_mesh(*shape.body_mesh));
    }
    const tools::TriangleMesh ground_mesh = tools::ground_mesh(simulation.scene.ground, kPlaneSize);
    if (!ground_mesh.triangles.empty()) ground = renderer.add_mesh(ground_mesh);
    sphere = renderer.add_mesh(tools::make_icosphere(1.0, 2));
  }
};

// Frames the bodies' starting positions: looks at their middle from far enough to see them all.
OrbitCamera frame_scene(const tools::Scene& scene) {
  OrbitCamera camera;
  if (scene.bodies.empty()) return camera;
  Eigen::AlignedBox3f box;
  for (const tools::BodySpec& body : scene.bodies) box.extend(body.position);
  camera.target = box.center();
  camera.target.y() = std::min(box.center().y(), 6.0f);
  const float size = std::max(box.sizes().maxCoeff(), 4.0f);
  camera.distance = std::clamp(1.1f * size, 12.0f, 150.0f);
  return camera;
}

// A soft dark disc on the ground under each body, fading with the body's height: enough to tell
// how high a body is and where it will land, at the cost of one flat sphere per body.
void draw_shadows(Renderer& renderer, const SceneGraphics& graphics, const Simulation& simulation) {
  const tools::GroundSpec& ground = simulation.scene.ground;
  const auto top = static_cast<float>(ground.height);
  const double half =
      ground.kind == tools::GroundSpec::Kind::kOctreeBox ? ground.size / 2.0 : kPlaneSize / 2.0;
  const tools::SimulationSetup& setup = simulation.setup;
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    const Vec3& position = setup.world->body(setup.bodies[i]).pose.translation;
    if (std::abs(position.x()) > half || std::abs(position.z()) > half) continue;
    const float height = position.y() - top;
    if (!(height > 0.0f)) continue;
    const float alpha = kShadowAlpha * std::max(0.0f, 1.0f - height / kShadowFade);
    if (alpha <= 0.0f) continue;
    const auto radius =
        static_cast<float>(0.8 * setup.shapes[setup.body_shape[i]].max_vertex_distance);
    Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
    model.diagonal() << radius, 0.002f, radius, 1.0f;
    model.block<3, 1>(0, 3) = Eigen::Vector3f(position.x(), top + 0.01f, position.z());
    renderer.draw(graphics.sphere, model, Eigen::Vector3f::Zero(), alpha);
  }
}

void draw_scene(Renderer& renderer, const SceneGraphics& graphics, const Simulation& simulation,
                const OrbitCamera& camera, float aspect, int sphere_level) {
  renderer.begin(camera.view(), camera.projection(aspect), camera.eye());
  const tools::SimulationSetup& setup = simulation.setup;
  if (graphics.ground) {
    renderer.draw(*graphics.ground, Eigen::Matrix4f::Identity(), kGroundColour);
    draw_shadows(renderer, graphics, simulation);
  }
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    const BodyId body = setup.bodies[i];
    const Eigen::Vector3f& colour = setup.world->asleep(body) ? kAsleepColour : kBodyColour;
    renderer.draw(graphics.shapes[setup.body_shape[i]], model_matrix(setup.world->body(body).pose),
                  colour);
  }
  if (sphere_level <= 0) return;
  // The overlay: the spheres of one level of each body's tree, see-through (level 1 is the root).
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    const SphereTree& tree = *setup.shapes[setup.body_shape[i]].tree;
    const int level = std::min(sphere_level, tree.depth()) - 1;
    const Transform& pose = setup.world->body(setup.bodies[i]).pose;
    for (const Sphere& sphere : tree.level_spheres(level)) {
      const Transform placed{pose.rotation, pose.apply(sphere.center)};
      renderer.draw(graphics.sphere, model_matrix(placed, sphere.radius), kSphereColour, 0.35f);
    }
  }
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

// The panel: what the step costs and finds, and the controls.
struct Controls {
  bool paused = false;
  bool step_once = false;
  bool reset = false;
  float speed = 1.0f;
  int sphere_level = 0;
};

void panel(const StepStats& stats, const Simulation& simulation, float fps, Controls& controls) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::Begin("sphys");
  ImGui::Text("%s, %zu bodies, %s", simulation.scene.name.c_str(), simulation.setup.bodies.size(),
              std::string(tools::response_mode_name(simulation.scene.response)).c_str());
  ImGui::Text("display %.0f fps, frame %d (%.2f s)", fps, simulation.frame,
              simulation.frame * simulation.scene.time_step);
  ImGui::Text("step %.2f ms: broad %.2f, narrow %.2f, contacts %.2f, response %.2f", stats.step_ms,
              stats.broad_phase_ms, stats.narrow_phase_ms, stats.contacts_ms, stats.response_ms);
  ImGui::Text("pairs %u, leaf pairs %u, contacts %u", stats.candidate_pairs, stats.leaf_pairs,
              stats.contacts);
  ImGui::Text("deepest %.4f m, at rest %u, asleep %u", stats.deepest_penetration,
              stats.bodies_at_rest, stats.bodies_asleep);
  ImGui::Checkbox("pause", &controls.paused);
  ImGui::SameLine();
  controls.step_once = ImGui::Button("step");
  ImGui::SameLine();
  controls.reset = ImGui::Button("reset");
  ImGui::SliderFloat("speed", &controls.speed, 0.1f, 2.0f);
  ImGui::SliderInt("sphere level", &controls.sphere_level, 0, 4);
  ImGui::End();
}

void interactive(Window& window, Renderer& renderer, Simulation& simulation,
                 const ViewerOptions& options) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui_ImplGlfw_InitForOpenGL(window.handle, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  glfwSwapInterval(1);

  SceneGraphics graphics(renderer, simulation);
  OrbitCamera camera = frame_scene(simulation.scene);
  Controls controls;
  controls.sphere_level = options.sphere_level;
  StepStats stats;
  double behind = 0.0;  // simulated time the display is ahead of the physics. unit: s
  Clock::time_point last = Clock::now();
  double mouse_x = 0.0;
  double mouse_y = 0.0;
  glfwGetCursorPos(window.handle, &mouse_x, &mouse_y);
  float fps = 0.0f;

  while (glfwWindowShouldClose(window.handle) == GLFW_FALSE) {
    glfwPollEvents();
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - last).count();
    last = now;
    fps = 0.9f * fps + 0.1f * static_cast<float>(elapsed > 0.0 ? 1.0 / elapsed : 0.0);

    // The mouse moves the camera unless the panel has it.
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window.handle, &x, &y);
    const auto dx = static_cast<float>(x - mouse_x);
    const auto dy = static_cast<float>(y - mouse_y);
    mouse_x = x;
    mouse_y = y;
    int width = 0;
    int height = 0;
    glfwGetFramebufferSize(window.handle, &width, &height);
    if (!ImGui::GetIO().WantCaptureMouse) {
      if (glfwGetMouseButton(window.handle, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        camera.turn(dx, dy);
      }
      if (glfwGetMouseButton(window.handle, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
          glfwGetMouseButton(window.handle, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) {
        camera.pan(dx, dy, static_cast<float>(std::max(height, 1)));
      }
      camera.zoom(ImGui::GetIO().MouseWheel);
    }

    if (controls.reset) {
      simulation.reset();
      behind = 0.0;
    }
    if (!controls.paused) behind += elapsed * controls.speed;
    int steps = 0;
    while ((behind >= simulation.scene.time_step || controls.step_once) &&
           steps < kMaxStepsPerFrame && !simulation.setup.world->stopped()) {
      stats = simulation.step();
      behind = std::max(0.0, behind - simulation.scene.time_step);
      controls.step_once = false;
      ++steps;
    }
    if (steps == kMaxStepsPerFrame) behind = 0.0;  // too slow for real time: fall behind

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    panel(stats, simulation, fps, controls);
    ImGui::Render();

    glViewport(0, 0, width, height);
    draw_scene(renderer, graphics, simulation, camera,
               static_cast<float>(width) / static_cast<float>(std::max(height, 1)),
               controls.sphere_level);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window.handle);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void screenshot(Window& window, Renderer& renderer, Simulation& simulation,
                const ViewerOptions& options) {
  for (int frame = 0; frame < options.frames; ++frame) {
    if (simulation.step().non_finite_body) {
      throw Error("the simulation went non-finite at frame " + std::to_string(frame + 1));
    }
  }
  SceneGraphics graphics(renderer, simulation);
  const OrbitCamera camera = frame_scene(simulation.scene);
  int width = 0;
  int height = 0;
  glfwGetFramebufferSize(window.handle, &width, &height);
  glViewport(0, 0, width, height);
  draw_scene(renderer, graphics, simulation, camera,
             static_cast<float>(width) / static_cast<float>(std::max(height, 1)),
             options.sphere_level);
  glFinish();
  write_png(*options.screenshot, width, height);
}

}  // namespace

void run_viewer(const ViewerOptions& options) {
  if (options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192) {
    throw Error("--width and --height must be between 16 and 8192");
  }
  if (options.frames < 0) throw Error("--frames must not be negative");
  if (options.sphere_level < 0) throw Error("--spheres must not be negative");
  Simulation simulation;
  simulation.scene = load(options);
  simulation.build.tree_depth = options.depth;
  if (options.use_cache) simulation.build.cache_dir = tools::default_cache_dir();
  simulation.reset();

  Window window(options.width, options.height);
  Renderer renderer;
  if (options.screenshot) {
    screenshot(window, renderer, simulation, options);
  } else {
    interactive(window, renderer, simulation, options);
  }
}

}  // namespace sphys::viewer
