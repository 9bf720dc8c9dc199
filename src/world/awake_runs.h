#pragma once

// A loop over the awake bodies on the threads that may stop the world: each body its own, and
// the body that stops it is the first in the awake order, whatever the thread count.

#include <cstdint>
#include <span>
#include <vector>

#include "core/buffers.h"
#include "sphys/parallel.h"

namespace sphys {

// Awake bodies per item of the threaded loop. unit: bodies
inline constexpr std::size_t kAwakeBodiesPerRun = 256;
// No body: every call returned true.
inline constexpr std::uint32_t kNoFailedBody = ~std::uint32_t{0};

// Calls ok(body) for every awake body, in runs on the threads; a run stops at its first body for
// which ok returns false. Returns the first such body in the awake order, or kNoFailedBody.
// `first_in_run` is scratch, one entry per run.
template <class Ok>
std::uint32_t first_failed_awake_body(std::span<const std::uint32_t> awake,
                                      const Parallel& parallel,
                                      std::vector<std::uint32_t>& first_in_run, const Ok& ok) {
  const std::size_t runs = (awake.size() + kAwakeBodiesPerRun - 1) / kAwakeBodiesPerRun;
  fill_buffer(first_in_run, runs, kNoFailedBody);
  parallel.for_each_run(awake.size(), kAwakeBodiesPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      if (ok(awake[k])) continue;
      first_in_run[begin / kAwakeBodiesPerRun] = awake[k];
      return;
    }
  });
  for (const std::uint32_t body : first_in_run) {
    if (body != kNoFailedBody) return body;
  }
  return kNoFailedBody;
}

}  // namespace sphys
