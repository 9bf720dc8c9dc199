#include "peak_memory.h"

#include <fstream>
#include <malloc.h>
#include <sstream>
#include <string>

namespace sphys::compare {
namespace {

// A "Name:   1234 kB" line of /proc/self/status. unit: KiB
std::optional<double> status_kib(const std::string& name) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (!line.starts_with(name + ":")) continue;
    std::istringstream fields(line.substr(name.size() + 1));
    double kib = 0.0;
    if (fields >> kib) return kib;
  }
  return std::nullopt;
}

}  // namespace

PeakMemory::PeakMemory() {
  // Memory an earlier run freed goes back to the system first: kept by the allocator, it would
  // serve this run's allocations without showing in the resident size.
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";  // resets the peak resident set size to the current one
  clear.flush();
  const std::optional<double> rss = status_kib("VmRSS");
  reset_ = clear.good() && rss.has_value();
  if (rss) start_kib_ = *rss;
}

std::optional<double> PeakMemory::added_mib() const {
  const std::optional<double> peak = status_kib("VmHWM");
  if (!reset_ || !peak) return std::nullopt;
  return (*peak - start_kib_) / 1024.0;
}

}  // namespace sphys::compare
