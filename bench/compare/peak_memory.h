#pragma once

// The resident memory a run adds at its peak, from Linux's counters: the high-water mark is reset
// before the run (/proc/self/clear_refs) and read after it (VmHWM) against the resident size at
// the start (VmRSS).

#include <optional>

namespace sphys::compare {

class PeakMemory {
 public:
  // Resets the high-water mark and remembers the resident size now.
  PeakMemory();
  // The peak resident size since construction less the size then; none where the kernel does
  // not let a process reset its mark. unit: MiB
  [[nodiscard]] std::optional<double> added_mib() const;

 private:
  bool reset_ = false;
  double start_kib_ = 0.0;
};

}  // namespace sphys::compare
