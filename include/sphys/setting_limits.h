#pragma once

// Limits of the world's settings that more than one place needs: the settings table
// (sphys/settings_table.h) checks against them, the contact reduction sizes its buffers by one.
// Each is declared here once.

#include <cstdint>

namespace sphys {

// Largest manifold a body pair may be reduced to (SolverSettings::manifold_points). unit: contacts
inline constexpr std::uint32_t kMaxManifoldPoints = 8;
// Most collision passes a step may run (WorldSettings::collision_passes and max_collision_passes):
// a step of 1/60 s cut 64 ways is 0.26 ms, finer than any scene sphys runs needs.
inline constexpr std::uint32_t kMaxCollisionPasses = 64;
// Most solver substeps a collision pass may run (SolverSettings::soft_substeps), for the same
// reason.
inline constexpr std::uint32_t kMaxSoftSubsteps = 64;
// Most passes over the contacts per collision pass in paper mode (WorldSettings::paper_passes).
// unit: passes
inline constexpr std::uint32_t kMaxPaperPasses = 1000;
// Largest magnitude of each component of gravity (WorldSettings::gravity), about 100 g: beyond
// any planet's, and small enough that a body falling freely for the longest run a scene may ask
// for (10⁷ steps of 1 s) stays finite in single precision. unit: m/s²
inline constexpr double kMaxGravity = 1000.0;
// More threads than any machine has is a mistake in the settings, not a wish
// (WorldSettings::threads).
inline constexpr std::uint32_t kMaxWorldThreads = 1024;

}  // namespace sphys
