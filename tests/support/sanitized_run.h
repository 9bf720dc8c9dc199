#pragma once

#include <cstdlib>

namespace sphys::test {

// True in the run under AddressSanitizer + UndefinedBehaviorSanitizer (the asan test preset sets
// SPHYS_SANITIZED_RUN). There the heaviest parameter sweeps keep one representative case: that
// run looks for memory and undefined-behaviour errors, which the same code paths reveal on one
// shape, while the release run checks every case.
inline bool sanitized_run() {
  const char* value = std::getenv("SPHYS_SANITIZED_RUN");
  return value != nullptr && *value != '\0' && *value != '0';
}

}  // namespace sphys::test
