#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "sphys/tools/experiment.h"

namespace sphys::tools {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double sum(std::span<const double> values) {
  double total = 0.0;
  for (const double v : values) total += v;
  return total;
}

// NaN for no values.
double mean(std::span<const double> values) {
  if (values.empty()) return kNaN;
  return sum(values) / static_cast<double>(values.size());
}

// The sample standard deviation (divisor n - 1), in two passes: deviations from the mean are
// squared, not the values, so large offsets (frame times around a big mean) lose no precision.
// NaN for fewer than two values.
double sample_sd(std::span<const double> values) {
  if (values.size() < 2) return kNaN;
  const double centre = mean(values);
  double squares = 0.0;
  for (const double v : values) squares += (v - centre) * (v - centre);
  return std::sqrt(squares / static_cast<double>(values.size() - 1));
}

// A percentage; NaN when nothing was measured to take a share of.
double share(double part, double whole) { return whole > 0.0 ? 100.0 * part / whole : kNaN; }

// Compared exactly: a computed mean of equal values may differ from them in the last bit, which
// would leave tiny deviations and a meaningless r.
bool has_spread(std::span<const double> values) {
  return std::ranges::any_of(values, [&](double v) { return v != values.front(); });
}

}  // namespace

double pearson(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size() || x.size() < 2 || !has_spread(x) || !has_spread(y)) return kNaN;
  const double mean_x = mean(x);
  const double mean_y = mean(y);
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - mean_x;
    const double dy = y[i] - mean_y;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (sxx == 0.0 || syy == 0.0) return kNaN;  // deviations too small to square (underflow)
  // The roots are taken apart so that sxx * syy cannot overflow; the clamp removes rounding
  // beyond ±1 on perfectly correlated data (NaN passes through).
  return std::clamp(sxy / (std::sqrt(sxx) * std::sqrt(syy)), -1.0, 1.0);
}

RowSummary summarize(const RowResult& result) {
  std::vector<double> step_ms;
  std::vector<double> detection_ms;
  std::vector<double> response_ms;
  std::vector<double> contacts;
  // The drawing of the frames sampled (every drawn_every-th), which must all have been drawn.
  std::vector<double> render_ms;
  bool sample_drawn = result.drawn_every > 0;
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    const FrameSample& frame = result.frames[i];
    if (result.drawn_every > 0 && (i + 1) % result.drawn_every == 0) {
      render_ms.push_back(frame.render_ms);
      sample_drawn = sample_drawn && frame.render_ms > 0.0;
    }
    step_ms.push_back(frame.step_ms);
    detection_ms.push_back(frame.detection_ms);
    response_ms.push_back(frame.response_ms);
    contacts.push_back(static_cast<double>(frame.contacts));
  }
  sample_drawn = sample_drawn && !render_ms.empty();
  RowSummary summary;
  summary.row = result.row;
  summary.contacts_per_frame = mean(contacts);
  summary.mean_frame_ms = mean(step_ms);
  summary.fps = summary.mean_frame_ms > 0.0 ? 1000.0 / summary.mean_frame_ms : kNaN;
  summary.frame_time_sd_ms = sample_sd(step_ms);
  const double total_ms = sum(step_ms);
  summary.detection_share = share(sum(detection_ms), total_ms);
  summary.response_share = share(sum(response_ms), total_ms);
  summary.frames_drawn = sample_drawn ? static_cast<std::uint32_t>(render_ms.size()) : 0;
  // Every frame drawn: the sum itself; a sample: its mean for every frame.
  const double all_render_ms =
      sample_drawn ? mean(render_ms) * static_cast<double>(result.frames.size()) : 0.0;
  const double drawn_ms = total_ms + all_render_ms;
  summary.fps_with_drawing = sample_drawn && drawn_ms > 0.0
                                 ? 1000.0 * static_cast<double>(result.frames.size()) / drawn_ms
                                 : kNaN;
  summary.drawing_share = sample_drawn ? share(all_render_ms, drawn_ms) : kNaN;
  summary.detection_share_drawn = sample_drawn ? share(sum(detection_ms), drawn_ms) : kNaN;
  summary.response_share_drawn = sample_drawn ? share(sum(response_ms), drawn_ms) : kNaN;
  return summary;
}

ExperimentStatistics compute_statistics(std::span<const RowSummary> rows) {
  std::vector<double> contacts;
  std::vector<double> fps;
  std::vector<double> frame_sd;
  std::vector<double> detection;
  std::vector<double> response;
  for (const RowSummary& row : rows) {
    contacts.push_back(row.contacts_per_frame);
    fps.push_back(row.fps);
    frame_sd.push_back(row.frame_time_sd_ms);
    detection.push_back(row.detection_share);
    response.push_back(row.response_share);
  }
  return {
      .contacts_fps_correlation = pearson(contacts, fps),
      .contacts_frame_sd_correlation = pearson(contacts, frame_sd),
      .detection_share_mean = mean(detection),
      .detection_share_sd = sample_sd(detection),
      .response_share_mean = mean(response),
      .response_share_sd = sample_sd(response),
      .detection_share_contacts_correlation = pearson(detection, contacts),
      .response_share_contacts_correlation = pearson(response, contacts),
  };
}

}  // namespace sphys::tools
