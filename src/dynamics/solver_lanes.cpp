// Which lanes the soft step solves with: the setting solver.lanes, SPHYS_SIMD from the
// environment, and what the processor has.

#include <cstdlib>
#include <string>

#include "dynamics/contact_lanes.h"
#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/solver_settings.h"

namespace sphys {
namespace {

bool processor_has_avx2() {
#if defined(__x86_64__) || defined(__i386__)
  // GCC's and Clang's check covers the operating system's saving of the AVX registers too.
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

bool have(SolverLanes lanes) {
  switch (lanes) {
    case SolverLanes::kAuto:
    case SolverLanes::kPortable:
      return true;
    case SolverLanes::kSse2:
#if defined(__SSE2__)
      return true;
#else
      return false;
#endif
    case SolverLanes::kAvx2:
      // The processor first: avx2_lane_kernels() is compiled for AVX2.
      return processor_has_avx2() && avx2_lane_kernels() != nullptr;
  }
  return false;
}

// SPHYS_SIMD's lanes; kAuto where it is unset, empty or "auto".
SolverLanes environment_lanes() {
  const char* text = std::getenv("SPHYS_SIMD");
  if (text == nullptr || *text == '\0') return SolverLanes::kAuto;
  const Setting& setting = setting_of("solver.lanes");
  for (std::size_t i = 0; i < setting.choices.size(); ++i) {
    if (setting.choices[i] == text) return static_cast<SolverLanes>(i);
  }
  throw Error("SPHYS_SIMD (environment) must be " + choices_text(setting) + ", got \"" +
              std::string(text) + "\"");
}

}  // namespace

std::string_view solver_lanes_name(SolverLanes lanes) {
  return setting_of("solver.lanes").choices[static_cast<std::size_t>(lanes)];
}

SolverLanes resolve_solver_lanes(SolverLanes requested) {
  std::string source = "solver.lanes";
  if (requested == SolverLanes::kAuto) {
    requested = environment_lanes();
    source = "SPHYS_SIMD (environment)";
  }
  if (requested == SolverLanes::kAuto) {
    if (have(SolverLanes::kAvx2)) return SolverLanes::kAvx2;
    return have(SolverLanes::kSse2) ? SolverLanes::kSse2 : SolverLanes::kPortable;
  }
  if (!have(requested)) {
    throw Error(source + " is " + std::string(solver_lanes_name(requested)) +
                ", which this processor or build does not have (it has " +
                (have(SolverLanes::kAvx2) ? "avx2, " : "") +
                (have(SolverLanes::kSse2) ? "sse2, " : "") + "portable)");
  }
  return requested;
}

}  // namespace sphys
