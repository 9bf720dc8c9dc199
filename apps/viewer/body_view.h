#pragma once

// One body as a displayed frame shows it, whether the frame comes from a live world or a
// recording.

#include <cstdint>

#include "sphys/math.h"

namespace sphys::viewer {

struct BodyView {
  std::uint32_t shape = 0;  // index into the shapes of the scene's SimulationSetup
  Transform pose;
  bool asleep = false;
};

}  // namespace sphys::viewer
