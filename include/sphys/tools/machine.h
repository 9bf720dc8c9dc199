#pragma once

// What machine a report's figures come from.

#include <string>

namespace sphys::tools {

// The processor a report's figures were measured on.
struct Machine {
  std::string cpu;                // the "model name" of the first processor in /proc/cpuinfo
  unsigned hardware_threads = 0;  // std::thread::hardware_concurrency(); 0 when it cannot tell
};

// The machine this runs on; cpu "unknown processor" where /proc/cpuinfo does not say.
[[nodiscard]] Machine this_machine();

// E.g. "AMD EPYC 7B13, 2 hardware threads".
[[nodiscard]] std::string machine_description();

// The machine as a folder name for its benchmark results: the processor's name in lower case,
// its runs of other characters as one '-', then the hardware threads, e.g. "amd-epyc-7b13-2t".
[[nodiscard]] std::string machine_folder();

}  // namespace sphys::tools
