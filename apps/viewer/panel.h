#pragma once

// The ImGui panels: what the step costs and finds, with small time plots, and the controls of a
// live run or of a replay.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene_drawer.h"
#include "sphys/step_stats.h"

namespace sphys::viewer {

// The last frames' step times and contact counts, for the plots.
class History {
 public:
  static constexpr int kFrames = 240;
  void add(const StepStats& stats);
  void clear();
  void plot() const;

 private:
  std::array<float, kFrames> step_ms_{};
  std::array<float, kFrames> contacts_{};
  int next_ = 0;
  int count_ = 0;
};

// What the user asks of a live run; the one-shot requests are cleared by the loop.
struct LiveControls {
  bool paused = false;
  float speed = 1.0f;
  Overlays overlays;
  // Scene switch, applied by `restart`: the index into `presets`, the depth, the mode.
  std::vector<std::string> presets;
  int preset = 0;
  int depth = 3;
  bool plausible = true;
  // Time-critical narrow phase: sphere tests and microseconds per step, 0 for no budget.
  int max_sphere_tests = 0;
  float max_microseconds = 0.0f;

  bool step_once = false;
  bool reset = false;
  bool restart = false;
  bool budget_changed = false;
  bool drop = false;
  bool shoot = false;
};

struct LiveStatus {
  std::string scene;
  std::size_t bodies = 0;
  bool plausible = true;
  bool can_add_bodies = false;
  int frame = 0;
  double time_step = 0.0;  // unit: s
  float fps = 0.0f;        // of the display
};

void live_panel(const LiveStatus& status, const StepStats& stats, const History& history,
                LiveControls& controls);

struct ReplayControls {
  bool playing = true;
  float speed = 1.0f;
  int frame = 0;
  Overlays overlays;
};

void replay_panel(const std::string& title, std::uint32_t frame_count, double time_step, float fps,
                  ReplayControls& controls);

}  // namespace sphys::viewer
