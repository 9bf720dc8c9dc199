// The lane choice: the setting solver.lanes, SPHYS_SIMD from the environment, and what the
// processor has.

#include "core/simd_lanes.h"

#include <cstddef>
#include <cstdlib>
#include <string>

#include "sphys/error.h"

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

bool have(SolverLanes lanes, bool avx2_compiled) {
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
      // The processor first: the AVX2 kernels are compiled for AVX2.
      return processor_has_avx2() && avx2_compiled;
  }
  return false;
}

// "auto, portable, sse2 or avx2", for messages.
std::string lane_set_names_text() {
  std::string text;
  for (std::size_t i = 0; i < kLaneSetNames.size(); ++i) {
    if (i > 0) text += i + 1 == kLaneSetNames.size() ? " or " : ", ";
    text += kLaneSetNames[i];
  }
  return text;
}

// SPHYS_SIMD's lanes; kAuto where it is unset, empty or "auto".
SolverLanes environment_lanes() {
  const char* text = std::getenv("SPHYS_SIMD");
  if (text == nullptr || *text == '\0') return SolverLanes::kAuto;
  for (std::size_t i = 0; i < kLaneSetNames.size(); ++i) {
    if (kLaneSetNames[i] == text) return static_cast<SolverLanes>(i);
  }
  throw Error("SPHYS_SIMD (environment) must be " + lane_set_names_text() + ", got \"" +
              std::string(text) + "\"");
}

}  // namespace

SolverLanes choose_lanes(SolverLanes requested, bool avx2_compiled) {
  std::string source = "solver.lanes";
  if (requested == SolverLanes::kAuto) {
    requested = environment_lanes();
    source = "SPHYS_SIMD (environment)";
  }
  if (requested == SolverLanes::kAuto) {
    if (have(SolverLanes::kAvx2, avx2_compiled)) return SolverLanes::kAvx2;
    return have(SolverLanes::kSse2, avx2_compiled) ? SolverLanes::kSse2 : SolverLanes::kPortable;
  }
  if (!have(requested, avx2_compiled)) {
    throw Error(source + " is " + std::string(kLaneSetNames[static_cast<std::size_t>(requested)]) +
                ", which this processor or build does not have (it has " +
                (have(SolverLanes::kAvx2, avx2_compiled) ? "avx2, " : "") +
                (have(SolverLanes::kSse2, avx2_compiled) ? "sse2, " : "") + "portable)");
  }
  return requested;
}

}  // namespace sphys
