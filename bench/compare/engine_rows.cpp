#include "engine_rows.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "sphys/tools/median.h"

namespace sphys::compare {
namespace {

using tools::median;

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// The frames every run of these engines ran (a run that failed counts none): all of them, unless
// one stopped at the time limit.
std::size_t common_frames(const Pooled& a, const Pooled& b) {
  std::size_t frames = std::numeric_limits<std::size_t>::max();
  for (const Pooled* pooled : {&a, &b}) {
    for (const RunResult& run : pooled->runs) frames = std::min(frames, run.step_ms.size());
  }
  return frames;
}

// Each run's first `frames` step times, pooled.
std::vector<double> first_frames(const Pooled& pooled, std::size_t frames) {
  std::vector<double> step_ms;
  for (const RunResult& run : pooled.runs) {
    step_ms.insert(step_ms.end(), run.step_ms.begin(),
                   run.step_ms.begin() + static_cast<std::ptrdiff_t>(frames));
  }
  return step_ms;
}

// A run's step times summed. unit: s
double seconds_of_steps(const RunResult& run) {
  return std::accumulate(run.step_ms.begin(), run.step_ms.end(), 0.0) / 1000.0;
}

// The plausibility figures, the worst over the runs, and the frames they ran.
void add_runs(const Pooled& pooled, int frames, EngineRow& row, std::vector<std::string>& stops) {
  RunResult& worst = row.worst;
  worst = pooled.runs.front();
  row.fewest_frames = row.most_frames = worst.step_ms.size();
  for (std::size_t r = 0; r < pooled.runs.size(); ++r) {
    const RunResult& run = pooled.runs[r];
    worst.deepest = std::max(worst.deepest, run.deepest);
    worst.deepest_last_second = std::max(worst.deepest_last_second, run.deepest_last_second);
    worst.end_overlap = std::max(worst.end_overlap, run.end_overlap);
    worst.largest_gap = std::max(worst.largest_gap, run.largest_gap);
    worst.largest_gap_at_end = std::max(worst.largest_gap_at_end, run.largest_gap_at_end);
    worst.largest_turn_error = std::max(worst.largest_turn_error, run.largest_turn_error);
    worst.mean_turn_error = std::max(worst.mean_turn_error, run.mean_turn_error);
    worst.largest_slide_error = std::max(worst.largest_slide_error, run.largest_slide_error);
    worst.kinetic_energy = std::max(worst.kinetic_energy, run.kinetic_energy);
    worst.moving = std::max(worst.moving, run.moving);
    worst.below = std::max(worst.below, run.below);
    if (worst.asleep && run.asleep) {
      worst.asleep = std::min(*worst.asleep, *run.asleep);
    } else {
      worst.asleep = std::nullopt;
    }
    if (run.peak_memory_mib) {
      worst.peak_memory_mib = std::max(worst.peak_memory_mib.value_or(0.0), *run.peak_memory_mib);
    }
    row.contacts_per_step += run.contacts_per_step;
    if (!run.warnings.empty()) worst.warnings = run.warnings;
    row.fewest_frames = std::min(row.fewest_frames, run.step_ms.size());
    row.most_frames = std::max(row.most_frames, run.step_ms.size());
    if (run.stopped) {
      stops.push_back(formatted("%s at frame %zu of %d (%.4g s of steps)", row.engine.c_str(),
                                run.step_ms.size(), frames, seconds_of_steps(run)));
      if (pooled.runs.size() > 1) stops.back() += formatted(" in run %zu", r + 1);
      row.stopped = true;
    }
  }
  row.contacts_per_step /= static_cast<double>(pooled.runs.size());
}

}  // namespace

std::string reference_engine(const std::vector<std::string>& engines) {
  if (std::find(engines.begin(), engines.end(), "sphys") != engines.end()) return "sphys";
  for (const std::string& engine : engines) {
    if (engine.starts_with("sphys:")) return engine;
  }
  return {};
}

SceneRows scene_rows(const std::string& layout, int depth, int frames,
                     const std::vector<std::string>& engines,
                     const std::map<std::string, Pooled>& results) {
  SceneRows scene{layout, depth, frames, reference_engine(engines), {}, {}};
  const Pooled* reference = scene.reference.empty() ? nullptr : &results.at(scene.reference);
  for (const std::string& engine : engines) {
    const Pooled& pooled = results.at(engine);
    EngineRow& row = scene.rows.emplace_back();
    row.engine = engine;
    if (pooled.step_ms.empty()) {
      row.worst.warnings = pooled.runs.front().warnings;
      continue;
    }
    row.ran = true;
    row.median_ms = median(pooled.step_ms);
    row.mean_ms = mean(pooled.step_ms);
    add_runs(pooled, frames, row, scene.stops);
    // Over the reference's times, over the frames both ran (a run that stopped at the time limit
    // ran only the first ones, and the first frames of a fall cost differently from the pile at
    // rest).
    const std::size_t common = reference == nullptr ? 0 : common_frames(pooled, *reference);
    if (common > 0) {
      const bool all = common == static_cast<std::size_t>(frames);
      const std::vector<double> ours = all ? pooled.step_ms : first_frames(pooled, common);
      const std::vector<double> theirs =
          all ? reference->step_ms : first_frames(*reference, common);
      row.ratio_frames = common;
      if (median(theirs) > 0.0) row.median_ratio = median(ours) / median(theirs);
      if (mean(theirs) > 0.0) row.mean_ratio = mean(ours) / mean(theirs);
    }
    row.us_per_body =
        row.worst.bodies > 0 ? 1000.0 * row.mean_ms / static_cast<double>(row.worst.bodies) : 0.0;
  }
  return scene;
}

}  // namespace sphys::compare
