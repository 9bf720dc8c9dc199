#include "viewer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "camera.h"
#include "lines.h"
#include "live_simulation.h"
#include "panel.h"
#include "renderer.h"
#include "replay.h"
#include "scene_drawer.h"
#include "sphys/error.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/tree_cache.h"
#include "window.h"

namespace sphys::viewer {
namespace {

using Clock = std::chrono::steady_clock;

// Physics steps one displayed frame may run at most, so that a slow step does not snowball.
constexpr int kMaxStepsPerFrame = 4;
// A body shot from the camera leaves this far in front of the eye at this speed. unit: m, m/s
constexpr float kShotStart = 1.5f;
constexpr float kShotSpeed = 25.0f;
// The paper's layouts, offered by the panel's scene switch.
const char* const kPresets[] = {"stacks:4x25", "stacks:4x50", "stacks:8x10", "stacks:8x20"};

tools::Scene make_scene(const std::string& source, std::optional<int> depth,
                        std::optional<ResponseMode> mode,
                        std::optional<tools::GroundSpec::Kind> ground) {
  tools::Scene scene = tools::load_scene(source);
  if (mode) scene.response = *mode;
  if (ground) scene.ground.kind = *ground;
  if (depth) {
    for (tools::BodySpec& body : scene.bodies) {
      if (!body.tree.sph_file) body.tree.depth = *depth;
    }
  }
  return scene;
}

tools::BuildWorldOptions build_options(const ViewerOptions& options) {
  tools::BuildWorldOptions build;
  build.tree_depth = options.depth;
  if (options.use_cache) build.cache_dir = tools::default_cache_dir();
  return build;
}

Overlays overlays_of(const ViewerOptions& options) {
  Overlays overlays;
  overlays.sphere_level = options.sphere_level;
  overlays.contacts = options.show_contacts;
  overlays.boxes = options.show_boxes;
  overlays.joints = options.show_joints;
  overlays.shadows = options.shadows;
  return overlays;
}

// The display's frame rate, smoothed, and the count and time of the frames shown, for
// --exit-after's report.
struct FrameClock {
  Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  float fps = 0.0f;
  int frames = 0;

  double tick() {  // returns the seconds since the last tick
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - last).count();
    last = now;
    fps =
        frames == 0 ? 0.0f : 0.9f * fps + 0.1f * static_cast<float>(1.0 / std::max(elapsed, 1e-6));
    ++frames;
    return elapsed;
  }
  [[nodiscard]] bool done(const ViewerOptions& options) const {
    return options.exit_after && frames >= *options.exit_after;
  }
  void report(double step_ms_sum, int steps) const {
    const double seconds = std::chrono::duration<double>(last - start).count();
    std::printf(
        "sphys view: %d frames displayed in %.2f s: %.1f frames/s; %d physics steps, "
        "%.3f ms each on average\n",
        frames, seconds, frames / std::max(seconds, 1e-9), steps,
        steps > 0 ? step_ms_sum / steps : 0.0);
  }
};

LiveControls initial_controls(const ViewerOptions& options, const tools::Scene& scene) {
  LiveControls controls;
  controls.presets.assign(std::begin(kPresets), std::end(kPresets));
  const auto known = std::find(controls.presets.begin(), controls.presets.end(), options.scene);
  if (known == controls.presets.end())
    controls.presets.insert(controls.presets.begin(), options.scene);
  controls.preset =
      static_cast<int>(std::find(controls.presets.begin(), controls.presets.end(), options.scene) -
                       controls.presets.begin());
  controls.depth = options.depth.value_or(scene.bodies.empty() ? 3 : scene.bodies[0].tree.depth);
  controls.plausible = scene.response == ResponseMode::kPlausible;
  controls.overlays = overlays_of(options);
  return controls;
}

// An interactive window and what draws in it; members go in the reverse order, the context last.
struct Display {
  Window window;
  Renderer renderer;
  LineRenderer lines;
  Gui gui;
  Input input;

  explicit Display(const ViewerOptions& options)
      : window(options.width, options.height, options.msaa), gui(window), input(window) {
    glfwSwapInterval(1);
  }
};

void run_live(const ViewerOptions& options, tools::Scene scene) {
  const tools::BuildWorldOptions build = build_options(options);
  auto simulation = std::make_unique<LiveSimulation>(std::move(scene), build);
  Display display(options);
  auto& [window, renderer, lines, gui, input] = display;
  auto drawer = std::make_unique<SceneDrawer>(renderer, simulation->scene(), simulation->shapes());
  OrbitCamera camera = frame_scene(simulation->scene());
  LiveControls controls = initial_controls(options, simulation->scene());
  History history;
  StepStats stats;
  std::mt19937 random(1);
  std::vector<BodyView> bodies;
  std::vector<Aabb> boxes;
  FrameClock clock;
  double behind = 0.0;  // simulated time the display is ahead of the physics. unit: s
  double step_ms_sum = 0.0;
  int steps_run = 0;

  while (!window.should_close() && !clock.done(options)) {
    glfwPollEvents();
    const double elapsed = clock.tick();
    input.update(window, gui, camera);
    if (input.pressed(GLFW_KEY_P)) controls.paused = !controls.paused;
    controls.step_once |= input.pressed(GLFW_KEY_N);
    controls.reset |= input.pressed(GLFW_KEY_R);
    controls.drop |= input.pressed(GLFW_KEY_B);
    if (input.pressed(GLFW_KEY_J)) controls.overlays.joints = !controls.overlays.joints;
    const bool shoot_at_cursor = input.pressed(GLFW_KEY_SPACE);

    if (controls.restart) {
      // Trees not in the cache are built here, which can take a while at depth 4 or more.
      tools::Scene next = make_scene(
          controls.presets[static_cast<std::size_t>(controls.preset)], controls.depth,
          controls.plausible ? ResponseMode::kPlausible : ResponseMode::kPaper, options.ground);
      tools::BuildWorldOptions next_build = build;
      next_build.tree_depth = controls.depth;
      drawer.reset();
      renderer.clear_meshes();
      simulation = std::make_unique<LiveSimulation>(std::move(next), next_build);
      drawer = std::make_unique<SceneDrawer>(renderer, simulation->scene(), simulation->shapes());
      camera = frame_scene(simulation->scene());
      controls.budget_changed = true;
    }
    if (controls.reset) simulation->reset();
    if (controls.reset || controls.restart) {
      history.clear();
      stats = StepStats{};
      behind = 0.0;
    }
    if (controls.budget_changed) {
      simulation->set_detection_budget(static_cast<std::uint64_t>(controls.max_sphere_tests),
                                       controls.max_microseconds);
    }
    if (controls.drop) simulation->drop_body(random);
    if (controls.shoot || shoot_at_cursor) {
      const Eigen::Vector3f direction =
          shoot_at_cursor
              ? camera.ray(static_cast<float>(input.x()), static_cast<float>(input.y()),
                           static_cast<float>(window.width()), static_cast<float>(window.height()))
              : (camera.target - camera.eye()).normalized();
      simulation->shoot_body(camera.eye() + kShotStart * direction, kShotSpeed * direction, random);
    }
    controls.reset = controls.restart = controls.budget_changed = false;
    controls.drop = controls.shoot = false;

    if (!controls.paused) behind += elapsed * controls.speed;
    const double time_step = simulation->scene().time_step;
    int steps = 0;
    while ((behind >= time_step || controls.step_once) && steps < kMaxStepsPerFrame &&
           !simulation->world().stopped()) {
      stats = simulation->step();
      history.add(stats);
      step_ms_sum += stats.step_ms;
      ++steps_run;
      behind = std::max(0.0, behind - time_step);
      controls.step_once = false;
      ++steps;
    }
    if (steps == kMaxStepsPerFrame) behind = 0.0;  // too slow for real time: fall behind

    gui.new_frame();
    LiveStatus status;
    status.scene = simulation->scene().name;
    status.bodies = simulation->body_count();
    status.plausible = simulation->world().settings().response == ResponseMode::kPlausible;
    status.can_add_bodies = simulation->can_add_bodies();
    status.frame = simulation->frame();
    status.time_step = time_step;
    status.fps = clock.fps;
    live_panel(status, stats, history, controls);

    simulation->bodies(bodies);
    if (controls.overlays.boxes) simulation->bounds(boxes);
    glViewport(0, 0, window.width(), window.height());
    drawer->draw(renderer, lines, camera, window.aspect(),
                 {bodies, simulation->world().contacts(), boxes, simulation->joints()},
                 controls.overlays);
    gui.render();
    glfwSwapBuffers(window.handle());
  }
  if (options.exit_after) clock.report(step_ms_sum, steps_run);
}

// --frames names a frame of the recording: past its end it is refused, as sphys export does.
void check_replay_frame(const ViewerOptions& options, const Replay& replay) {
  if (options.frames >= static_cast<int>(replay.frame_count())) {
    throw Error(options.replay->string() + ": --frames " + std::to_string(options.frames) +
                " is past the recording's last frame, " + std::to_string(replay.frame_count() - 1));
  }
}

void run_replay(const ViewerOptions& options) {
  const Replay replay(*options.replay, build_options(options));
  check_replay_frame(options, replay);
  Display display(options);
  auto& [window, renderer, lines, gui, input] = display;
  SceneDrawer drawer(renderer, replay.scene(), replay.shapes());
  OrbitCamera camera = frame_scene(replay.scene());
  ReplayControls controls;
  controls.overlays = overlays_of(options);
  controls.frame = options.frames;
  const int last = static_cast<int>(replay.frame_count()) - 1;
  const std::string title = options.replay->filename().string() + ": " + replay.scene().name +
                            ", " + std::to_string(replay.scene().bodies.size()) + " bodies";
  std::vector<BodyView> bodies;
  FrameClock clock;
  double position = controls.frame;  // in frames, fractional between displayed frames

  while (!window.should_close() && !clock.done(options)) {
    glfwPollEvents();
    const double elapsed = clock.tick();
    input.update(window, gui, camera);
    if (input.pressed(GLFW_KEY_P) || input.pressed(GLFW_KEY_SPACE)) {
      controls.playing = !controls.playing;
    }
    if (input.pressed(GLFW_KEY_J)) controls.overlays.joints = !controls.overlays.joints;
    if (input.pressed(GLFW_KEY_LEFT)) controls.frame = std::max(0, controls.frame - 1);
    if (input.pressed(GLFW_KEY_RIGHT)) controls.frame = std::min(last, controls.frame + 1);
    if (std::floor(position) != controls.frame) position = controls.frame;  // the slider moved
    if (controls.playing) {
      position = std::min<double>(last, position + elapsed * controls.speed / replay.time_step());
      controls.frame = static_cast<int>(position);
      if (controls.frame == last) controls.playing = false;
    }

    gui.new_frame();
    replay_panel(title, replay.frame_count(), replay.time_step(), clock.fps, controls);
    replay.bodies(static_cast<std::uint32_t>(controls.frame), bodies);
    glViewport(0, 0, window.width(), window.height());
    drawer.draw(renderer, lines, camera, window.aspect(), {bodies, {}, {}, replay.joints()},
                controls.overlays);
    gui.render();
    glfwSwapBuffers(window.handle());
  }
  if (options.exit_after) clock.report(0.0, 0);
}

void draw_and_save(const Window& window, Renderer& renderer, SceneDrawer& drawer,
                   const tools::Scene& scene, const FrameContents& frame, const Overlays& overlays,
                   const std::filesystem::path& path) {
  LineRenderer lines;
  glViewport(0, 0, window.width(), window.height());
  drawer.draw(renderer, lines, frame_scene(scene), window.aspect(), frame, overlays);
  glFinish();
  write_png(path, window.width(), window.height());
}

void live_screenshot(const ViewerOptions& options, tools::Scene scene) {
  LiveSimulation simulation(std::move(scene), build_options(options));
  for (int frame = 0; frame < options.frames; ++frame) {
    if (simulation.step().non_finite_body) {
      throw Error("the simulation went non-finite at frame " + std::to_string(frame + 1));
    }
  }
  std::vector<BodyView> bodies;
  std::vector<Aabb> boxes;
  simulation.bodies(bodies);
  simulation.bounds(boxes);
  const Window window(options.width, options.height, options.msaa);
  Renderer renderer;
  SceneDrawer drawer(renderer, simulation.scene(), simulation.shapes());
  draw_and_save(window, renderer, drawer, simulation.scene(),
                {bodies, simulation.world().contacts(), boxes, simulation.joints()},
                overlays_of(options), *options.screenshot);
}

void replay_screenshot(const ViewerOptions& options) {
  const Replay replay(*options.replay, build_options(options));
  check_replay_frame(options, replay);
  std::vector<BodyView> bodies;
  replay.bodies(static_cast<std::uint32_t>(options.frames), bodies);
  const Window window(options.width, options.height, options.msaa);
  Renderer renderer;
  SceneDrawer drawer(renderer, replay.scene(), replay.shapes());
  draw_and_save(window, renderer, drawer, replay.scene(), {bodies, {}, {}, replay.joints()},
                overlays_of(options), *options.screenshot);
}

}  // namespace

void run_viewer(const ViewerOptions& options) {
  check_window_size(options.width, options.height);
  if (options.frames < 0) throw Error("--frames must not be negative");
  if (options.sphere_level < 0) throw Error("--spheres must not be negative");
  if (options.exit_after && *options.exit_after < 1) throw Error("--exit-after must be at least 1");
  if (options.msaa && (*options.msaa < 0 || *options.msaa > 16)) {
    throw Error("--msaa must be between 0 and 16");
  }
  if (options.replay) {
    if (options.screenshot) {
      replay_screenshot(options);
    } else {
      run_replay(options);
    }
    return;
  }
  tools::Scene scene = make_scene(options.scene, options.depth, options.mode, options.ground);
  if (options.screenshot) {
    live_screenshot(options, std::move(scene));
  } else {
    run_live(options, std::move(scene));
  }
}

}  // namespace sphys::viewer
