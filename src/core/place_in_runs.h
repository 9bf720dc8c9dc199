#pragma once

// Lists built on the threads with the serial loop's result: each item takes a number of places
// in order, found run by run (a scan, as Blelloch's, of one level): each run of items sums what
// its items take, a prefix sum over the runs gives each run its first place, and each run then
// writes from there.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/buffers.h"
#include "sphys/parallel.h"

namespace sphys {

// Calls size(total) with the places of all items [0, count), then place(first, k) for every k with
// places(k) > 0, first being the places of the items before k; returns the total. places() is
// called twice per item and must give the same answer both times; place() of different items
// must not touch the same memory. `run_first` is scratch, kept by the caller so that a step need
// not allocate. On one thread, or with one run, it is the serial loop, in one pass: size(most),
// `most` bounding the total, then size(total) once the items are placed (on one thread, timed as
// a loop where more threads would have shared it: Parallel::as_one_run).
template <class Places, class Size, class Place>
std::size_t place_in_runs(const Parallel& parallel, std::size_t count, std::size_t run,
                          std::size_t most, const Places& places, const Size& size,
                          const Place& place, std::vector<std::uint32_t>& run_first) {
  if (parallel.threads() == 1 || count <= run) {
    size(most);
    std::size_t first = 0;
    const auto one_pass = [&] {
      for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t taken = places(k);
        if (taken > 0) place(first, k);
        first += taken;
      }
    };
    parallel.as_one_run(one_pass, count > run);
    size(first);
    return first;
  }
  const std::size_t runs = (count + run - 1) / run;
  fill_buffer(run_first, runs + 1, 0u);
  parallel.for_each_run(count, run, [&](std::size_t begin, std::size_t end) {
    std::uint32_t taken = 0;
    for (std::size_t k = begin; k < end; ++k) taken += places(k);
    run_first[begin / run + 1] = taken;
  });
  for (std::size_t r = 0; r < runs; ++r) run_first[r + 1] += run_first[r];
  size(std::size_t{run_first[runs]});
  parallel.for_each_run(count, run, [&](std::size_t begin, std::size_t end) {
    std::size_t first = run_first[begin / run];
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t taken = places(k);
      if (taken > 0) place(first, k);
      first += taken;
    }
  });
  return run_first[runs];
}

// The indices k in [0, count) with keep(k), in order: size(kept), then place(position, k) for
// each, position counting from 0; returns how many. As place_in_runs.
template <class Keep, class Size, class Place>
std::size_t compact_in_runs(const Parallel& parallel, std::size_t count, std::size_t run,
                            const Keep& keep, const Size& size, const Place& place,
                            std::vector<std::uint32_t>& run_first) {
  return place_in_runs(
      parallel, count, run, count, [&](std::size_t k) { return keep(k) ? 1u : 0u; }, size, place,
      run_first);
}

}  // namespace sphys
