#include "collision/crowd.h"

#include <algorithm>

namespace sphys {

std::size_t Crowd::nearest_kept() const { return std::max<std::size_t>(1, limit_ / 2); }

void Crowd::begin_nearest(std::size_t ids, std::vector<std::uint64_t>& listed) {
  listed.clear();
  nearest_.assign(ids * nearest_kept(), Partner{});
  nearest_count_.assign(ids, 0);
}

// Keeps a box's nearest partners as a bounded max-heap: the farthest is the first to go.
void Crowd::offer_nearest(ProxyId id, const Partner& partner) {
  const std::size_t kept = nearest_kept();
  Partner* heap = nearest_.data() + std::size_t{id} * kept;
  std::uint32_t& count = nearest_count_[id];
  if (count < kept) {
    heap[count++] = partner;
    std::push_heap(heap, heap + count);
  } else if (partner < heap[0]) {
    std::pop_heap(heap, heap + count);
    heap[count - 1] = partner;
    std::push_heap(heap, heap + count);
  }
}

void Crowd::list_nearest(std::uint64_t overlapping, std::vector<std::uint64_t>& listed) {
  const std::size_t kept = nearest_kept();
  for (ProxyId id = 0; id < nearest_count_.size(); ++id) {
    const Partner* heap = nearest_.data() + std::size_t{id} * kept;
    for (std::uint32_t i = 0; i < nearest_count_[id]; ++i) {
      listed.push_back(pair_key(id, heap[i].other));
    }
  }
  std::sort(listed.begin(), listed.end());
  listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
  pairs_deferred_ = overlapping - listed.size();
}

}  // namespace sphys
