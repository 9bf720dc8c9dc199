// The paper's step (§4): gravity, detection, eq. 4 per contact in order, positions. Its collision
// passes are as many as WorldSettings::collision_passes asks, always.

#include <array>

#include "world/pipeline.h"
#include "world/stages.h"
#include "world/world_state.h"

namespace sphys {
namespace {

constexpr auto kPaperPass = std::to_array<Stage>({
    {"integrate velocities", integrate_velocities},
    {"detect", detect_contacts},
    {"apply impulses", apply_paper_impulses},
    {"integrate positions", integrate_positions},
});

std::uint32_t paper_collision_passes(const WorldState& world, float /*dt*/) {
  return world.settings.collision_passes;
}

constexpr Pipeline kPaper{
    .collision_passes = paper_collision_passes,
    .start_step = nullptr,
    .pass = kPaperPass,
};

}  // namespace

const Pipeline& paper_pipeline() { return kPaper; }

}  // namespace sphys
