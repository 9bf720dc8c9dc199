#pragma once

// Figures of one World::step: every figure the experiment reports, each measured once.

#include <cstdint>
#include <optional>

namespace sphys {

struct StepStats {
  // Wall-clock time of each phase of the step and of the whole step. unit: ms
  double broad_phase_ms = 0.0;   // bounds and Sweep & Prune
  double narrow_phase_ms = 0.0;  // sphere-tree descents (leaf pairs)
  double contacts_ms = 0.0;      // contact point, normal and depth per leaf pair (eq. 1-3)
  double response_ms = 0.0;      // impulses
  double integration_ms = 0.0;   // velocities and positions
  double step_ms = 0.0;          // the whole step
  // Detection as the paper counts it: broad phase, narrow phase and contacts. unit: ms
  [[nodiscard]] double detection_ms() const {
    return broad_phase_ms + narrow_phase_ms + contacts_ms;
  }

  std::uint32_t bodies = 0;
  std::uint32_t candidate_pairs = 0;  // overlapping bounds from the broad phase
  std::uint64_t sphere_tests = 0;
  std::uint32_t leaf_pairs = 0;
  std::uint32_t contacts = 0;
  std::uint32_t impulses = 0;         // impulses applied, over all passes
  std::uint32_t response_passes = 0;  // passes over the contacts (paper mode)
  std::uint32_t pairs_cut_short = 0;
  std::uint32_t coincident_centres = 0;

  double kinetic_energy = 0.0;  // after the step, all moving bodies. unit: J
  float deepest_penetration =
      0.0f;  // largest contact depth this step (0 without contacts). unit: m

  // The first body (by index) whose state stopped being finite (or whose orientation stopped
  // being a rotation) in this step; the world stops stepping from then on. Unset while all is well.
  std::optional<std::uint32_t> non_finite_body;
};

}  // namespace sphys
