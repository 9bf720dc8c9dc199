#pragma once

// A QueryFilter checked body by body, its ids checked once against the query's snapshot.

#include <algorithm>
#include <cstdint>
#include <string_view>
#include <vector>

#include "query/snapshot.h"
#include "sphys/world_query.h"

namespace sphys::query_detail {

class BodyFilter {
 public:
  // Throws sphys::Error naming `filter.skip` for a body that was not in the world when the
  // snapshot was made.
  BodyFilter(const Snapshot& snapshot, const QueryFilter& filter);

  [[nodiscard]] bool sees(std::uint32_t slot) const {
    const std::uint32_t category = slot < filter_.categories.size() ? filter_.categories[slot] : 1u;
    if ((category & filter_.mask) == 0) return false;
    if (filter_.skip_sleeping && snapshot_.asleep[slot] != 0) return false;
    return std::ranges::find(skip_, slot) == skip_.end();
  }

 private:
  const Snapshot& snapshot_;
  const QueryFilter& filter_;
  std::vector<std::uint32_t> skip_;  // slots
};

// The slot of a body in the world as the snapshot saw it: the query reads the snapshot alone, so
// that it may run while the world steps. Throws sphys::Error naming `argument` for the null id, a
// stale or unknown one, or one added after the snapshot was made.
[[nodiscard]] std::uint32_t checked_slot(const Snapshot& snapshot, BodyId body,
                                         std::string_view argument);

}  // namespace sphys::query_detail
