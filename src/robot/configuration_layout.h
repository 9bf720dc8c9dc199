#pragma once

// How the batched checks lay out and hand out their work (configuration_check.cpp,
// robot_check.cpp).

#include <cstddef>

namespace sphys {

// A posed sphere's floats: x, y, z, radius.
inline constexpr std::size_t kFloatsPerSphere = 4;

// Configurations per task on the threads: one is too little work to hand out. unit:
// configurations
inline constexpr std::size_t kConfigurationsPerRun = 64;

}  // namespace sphys
