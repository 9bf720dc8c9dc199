#pragma once

// What machine a report's figures come from.

#include <string>

namespace sphys::tools {

// The "model name" of the first processor in /proc/cpuinfo and the hardware threads, e.g.
// "AMD EPYC 7B13, 2 hardware threads".
[[nodiscard]] std::string machine_description();

}  // namespace sphys::tools
