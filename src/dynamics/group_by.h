#pragma once

// Items listed group by group, for solving islands apart.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/buffers.h"

namespace sphys {

// The group of an item that belongs to none.
inline constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();

// Lists items 0..count-1 by group (a counting sort): group g's items are
// items[begin[g], begin[g + 1]), in their own order. `group_of(k)` is item k's group, < groups,
// or kNoGroup to leave it out.
template <class GroupOf>
void group_by(std::size_t count, std::size_t groups, const GroupOf& group_of,
              std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& items) {
  fill_buffer(begin, groups + 1, 0u);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t group = group_of(k);
    if (group != kNoGroup) ++begin[group + 1];
  }
  for (std::size_t g = 0; g < groups; ++g) begin[g + 1] += begin[g];
  resize_buffer(items, begin[groups]);
  // begin[g] serves as group g's next free place, then is moved back to where group g starts.
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t group = group_of(k);
    if (group != kNoGroup) items[begin[group]++] = static_cast<std::uint32_t>(k);
  }
  for (std::size_t g = groups; g > 0; --g) begin[g] = begin[g - 1];
  begin[0] = 0;
}

// Runs longer than this keep their own order after their first kRunRanks - 1 items.
inline constexpr std::uint32_t kRunRanks = 8;

// Like group_by, but within a group the items are listed by their place in their run (a run:
// consecutive items with `continues_run(k)` true for all but its first, such as one body pair's
// contacts): every run's first item, then every run's second, and so on, each rank in the items'
// order. Sequential impulses solved in this order rarely meet two constraints in a row that share
// a body, so the processor overlaps one constraint's arithmetic with the next one's instead of
// waiting for the velocities the last one wrote. `rank` and `fine_begin` are scratch buffers.
template <class GroupOf, class ContinuesRun>
void group_by_interleaving_runs(std::size_t count, std::size_t groups, const GroupOf& group_of,
                                const ContinuesRun& continues_run, std::vector<std::uint32_t>& rank,
                                std::vector<std::uint32_t>& fine_begin,
                                std::vector<std::uint32_t>& begin,
                                std::vector<std::uint32_t>& items) {
  resize_buffer(rank, count);
  for (std::size_t k = 0; k < count; ++k) {
    rank[k] = k > 0 && continues_run(k) ? std::min(rank[k - 1] + 1, kRunRanks - 1) : 0;
  }
  group_by(
      count, groups * kRunRanks,
      [&](std::size_t k) {
        const std::uint32_t group = group_of(k);
        return group == kNoGroup ? kNoGroup : group * kRunRanks + rank[k];
      },
      fine_begin, items);
  resize_buffer(begin, groups + 1);
  for (std::size_t g = 0; g <= groups; ++g) begin[g] = fine_begin[g * kRunRanks];
}

}  // namespace sphys
