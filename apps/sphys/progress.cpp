#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

#include "sphys/tools/interrupt.h"

namespace sphys::cli {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void ProgressBar::note(const std::string& line) {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

void ProgressBar::update(double fraction) {
  // Every long loop reports its progress here, so this is where it notices Ctrl-C.
  tools::throw_if_interrupted();
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100) && fraction < 1.0) return;
  last_draw_ = now;
  drawn_ = true;
  constexpr int kWidth = 30;
  const double clamped = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(clamped * kWidth);
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled,
               "##############################", kWidth - filled, "",
               static_cast<int>(clamped * 100.0));
  std::fflush(stderr);
}

}  // namespace sphys::cli
