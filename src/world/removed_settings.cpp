// The settings that were removed, each with what replaced it: a scene or a command that names one
// is refused with that (docs/scenes.md, the solver's section).

#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "sphys/settings_table.h"

namespace sphys {
namespace {

constexpr auto kRemoved = std::to_array<RemovedSetting>({
    // The world's outer loop is collision passes; "substeps" are the solver's own alone.
    {"substeps", "renamed collision_passes"},
    {"max_substeps", "renamed max_collision_passes"},
    {"substep_travel", "renamed collision_pass_travel"},
    // The settings of the sequential-impulse solver, which the soft step replaced as the
    // plausible mode's only solver.
    {"solver.method", "the soft step is the only solver; delete the setting"},
    {"solver.velocity_iterations",
     "the soft step solves and relaxes each contact once per substep; set solver.soft_substeps"},
    {"solver.substep_velocity_iterations",
     "the soft step solves and relaxes each contact once per substep; set solver.soft_substeps"},
    {"solver.position_iterations",
     "the soft step's contact springs push bodies apart; set solver.contact_hertz and "
     "solver.contact_damping_ratio"},
    {"solver.position_correction",
     "the soft step's contact springs push bodies apart; set solver.contact_hertz and "
     "solver.contact_damping_ratio"},
    {"solver.shock_propagation",
     "the soft step's relax passes and stiffer springs against immovable bodies carry a pile's "
     "weight; delete the setting"},
    {"solver.shock_speed",
     "the soft step's relax passes and stiffer springs against immovable bodies carry a pile's "
     "weight; delete the setting"},
});

}  // namespace

const RemovedSetting* removed_setting(std::string_view field) {
  const auto found =
      std::find_if(kRemoved.begin(), kRemoved.end(),
                   [&](const RemovedSetting& removed) { return removed.field == field; });
  return found == kRemoved.end() ? nullptr : &*found;
}

std::string removed_setting_message(const RemovedSetting& removed) {
  return std::string(removed.field) + " was removed: " + std::string(removed.replacement);
}

}  // namespace sphys
