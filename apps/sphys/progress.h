#pragma once

#include <chrono>
#include <string>

namespace sphys::cli {

// A one-line progress bar on standard error, drawn only when standard error is a terminal (so
// logs and pipes stay clean). Redraws at most a few times a second.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Draws `fraction` (0..1); throws tools::Interrupted when Ctrl-C or SIGTERM came in the
  // meantime (see sphys/tools/interrupt.h).
  void update(double fraction);
  // Prints a line of its own on standard error (whether or not it is a terminal), the bar, if
  // drawn, cleared first and drawn again at the next update().
  void note(const std::string& line);

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace sphys::cli
