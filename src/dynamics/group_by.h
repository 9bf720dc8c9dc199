#pragma once

// Items listed group by group, for solving islands apart.

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

}  // namespace sphys
