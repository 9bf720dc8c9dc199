#pragma once

// Which SIMD lanes the library's kernels run in, chosen in one place for the soft step's contact
// passes (dynamics) and the robot kinematics (robot) alike: the lane sets' names, SPHYS_SIMD from
// the environment and what the processor has. Every choice computes the same bits; they differ in
// speed only.

#include <array>
#include <string_view>

#include "sphys/solver_settings.h"

namespace sphys {

// The lane sets' names, by SolverLanes value: the words of the setting solver.lanes and of
// SPHYS_SIMD.
inline constexpr std::array<std::string_view, 4> kLaneSetNames = {"auto", "portable", "sse2",
                                                                  "avx2"};

// The lanes to run: `requested` (the setting solver.lanes) where it is not kAuto, else SPHYS_SIMD's
// where it is set and not "auto", else the widest this processor has. `avx2_compiled`: whether the
// caller's AVX2 kernels are in this build (their one file is compiled for AVX2 on x86-64 only).
// Throws sphys::Error for lanes this processor or build lacks, or an SPHYS_SIMD it cannot read,
// naming what was asked and what there is.
[[nodiscard]] SolverLanes choose_lanes(SolverLanes requested, bool avx2_compiled);

}  // namespace sphys
