#include "collision/crowd.h"

#include <algorithm>

namespace sphys {

std::size_t Crowd::nearest_kept() const { return std::max<std::size_t>(1, limit_ / 2); }

std::uint64_t Crowd::count_overlaps(std::size_t ids) {
  overlaps_.assign(ids, 0);
  std::uint64_t ends = 0;  // each pair counted from both of its boxes
  for (const ProxyId id : alive_) {
    overlaps_[id] = tree_.count_overlaps(id);
    ends += overlaps_[id];
  }
  return ends / 2;
}

void Crowd::list_chosen(std::vector<std::uint64_t>& listed) {
  tree_.mark(choosing_);
  const std::size_t kept = nearest_kept();
  for (const ProxyId id : alive_) {
    if (choosing_[id] != 0) {
      tree_.nearest(id, kept, nearest_);
      for (const CrowdPartner& partner : nearest_) listed.push_back(pair_key(id, partner.other));
      continue;
    }
    // Every pair of a box not choosing, from its lower id when neither chooses.
    tree_.for_each_overlap(id, [&](ProxyId other) {
      if (choosing_[other] != 0 || id < other) listed.push_back(pair_key(id, other));
    });
  }
  std::sort(listed.begin(), listed.end());
  listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
}

}  // namespace sphys
