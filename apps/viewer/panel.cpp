#include "panel.h"

#include <algorithm>
#include <imgui.h>

namespace sphys::viewer {
namespace {

// The overlays' toggles; replays have no contacts or broad-phase boxes to show.
void overlay_controls(Overlays& overlays, bool live) {
  ImGui::SliderInt("sphere level", &overlays.sphere_level, 0, 6,
                   overlays.sphere_level == 0 ? "off" : "%d");
  ImGui::Checkbox("shadows", &overlays.shadows);
  ImGui::SameLine();
  ImGui::Checkbox("joints (J)", &overlays.joints);
  if (live) {
    ImGui::SameLine();
    ImGui::Checkbox("contacts", &overlays.contacts);
    ImGui::SameLine();
    ImGui::Checkbox("boxes", &overlays.boxes);
    ImGui::SameLine();
    ImGui::Checkbox("sleep tint", &overlays.sleeping_tint);
  }
}

// Plots `count` values of a ring buffer whose oldest is at `start`.
void plot_ring(const char* label, const std::array<float, History::kFrames>& values, int start,
               int count, const char* format) {
  float latest =
      count > 0 ? values[static_cast<std::size_t>((start + count - 1) % History::kFrames)] : 0.0f;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, format, static_cast<double>(latest));
  ImGui::PlotLines(label, values.data(), count, count < History::kFrames ? 0 : start, overlay, 0.0f,
                   FLT_MAX, ImVec2(0, 48));
}

}  // namespace

void History::add(const StepStats& stats) {
  step_ms_[static_cast<std::size_t>(next_)] = static_cast<float>(stats.step_ms);
  contacts_[static_cast<std::size_t>(next_)] = static_cast<float>(stats.contacts);
  next_ = (next_ + 1) % kFrames;
  count_ = std::min(count_ + 1, kFrames);
}

void History::clear() {
  next_ = 0;
  count_ = 0;
}

void History::plot() const {
  const int start = count_ < kFrames ? 0 : next_;
  plot_ring("step ms", step_ms_, start, count_, "%.2f ms");
  plot_ring("contacts", contacts_, start, count_, "%.0f");
}

void live_panel(const LiveStatus& status, const StepStats& stats, const History& history,
                LiveControls& controls) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(420, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("sphys");
  ImGui::Text("%s, %zu bodies, %s", status.scene.c_str(), status.bodies,
              status.plausible ? "plausible" : "paper");
  ImGui::Text("display %.0f fps, frame %d (%.2f s)", static_cast<double>(status.fps), status.frame,
              status.frame * status.time_step);
  ImGui::Text("step %.2f ms: broad %.2f, narrow %.2f, contacts %.2f, response %.2f", stats.step_ms,
              stats.broad_phase_ms, stats.narrow_phase_ms, stats.contacts_ms, stats.response_ms);
  ImGui::Text("pairs %u, leaf pairs %u, contacts %u, cut short %u", stats.candidate_pairs,
              stats.leaf_pairs, stats.contacts, stats.pairs_cut_short);
  ImGui::Text("deepest %.4f m, at rest %u, asleep %u",
              static_cast<double>(stats.deepest_penetration), stats.bodies_at_rest,
              stats.bodies_asleep);
  history.plot();

  ImGui::Separator();
  ImGui::Checkbox("pause (P)", &controls.paused);
  ImGui::SameLine();
  controls.step_once = ImGui::Button("step (N)") || controls.step_once;
  ImGui::SameLine();
  controls.reset = ImGui::Button("reset (R)") || controls.reset;
  ImGui::SliderFloat("speed", &controls.speed, 0.1f, 2.0f, "%.2f×");
  if (status.can_add_bodies) {
    controls.drop = ImGui::Button("drop a body (B)") || controls.drop;
    ImGui::SameLine();
    controls.shoot = ImGui::Button("shoot one (space)") || controls.shoot;
  }

  ImGui::Separator();
  overlay_controls(controls.overlays, true);

  ImGui::Separator();
  ImGui::Text("time-critical narrow phase (0: exact)");
  controls.budget_changed = ImGui::SliderInt("sphere tests", &controls.max_sphere_tests, 0, 1000000,
                                             "%d", ImGuiSliderFlags_Logarithmic) ||
                            controls.budget_changed;
  controls.budget_changed = ImGui::SliderFloat("µs", &controls.max_microseconds, 0.0f, 20000.0f,
                                               "%.0f", ImGuiSliderFlags_Logarithmic) ||
                            controls.budget_changed;

  ImGui::Separator();
  const auto preset_name = [](void* data, int i, const char** out) {
    *out = (*static_cast<std::vector<std::string>*>(data))[static_cast<std::size_t>(i)].c_str();
    return true;
  };
  ImGui::Combo("scene", &controls.preset, preset_name, &controls.presets,
               static_cast<int>(controls.presets.size()));
  ImGui::SliderInt("depth", &controls.depth, 1, 5);
  ImGui::Checkbox("plausible response", &controls.plausible);
  controls.restart = ImGui::Button("restart with these") || controls.restart;
  ImGui::End();
}

void replay_panel(const std::string& title, std::uint32_t frame_count, double time_step, float fps,
                  ReplayControls& controls) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(420, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("sphys replay");
  ImGui::Text("%s", title.c_str());
  ImGui::Text("display %.0f fps, frame %d of %u (%.2f s)", static_cast<double>(fps), controls.frame,
              frame_count, controls.frame * time_step);
  ImGui::SliderInt("frame", &controls.frame, 0, static_cast<int>(frame_count) - 1);
  ImGui::Checkbox("play (P)", &controls.playing);
  ImGui::SameLine();
  if (ImGui::Button("start")) controls.frame = 0;
  ImGui::SliderFloat("speed", &controls.speed, 0.1f, 4.0f, "%.2f×");
  ImGui::Separator();
  overlay_controls(controls.overlays, false);
  ImGui::End();
}

}  // namespace sphys::viewer
