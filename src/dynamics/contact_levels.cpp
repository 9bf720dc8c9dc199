#include "dynamics/contact_levels.h"

#include "core/buffers.h"

namespace sphys {

std::span<const std::uint32_t> ContactLevels::compute(
    std::span<const std::uint8_t> immovable,
    std::span<const std::pair<std::uint32_t, std::uint32_t>> contacts) {
  const std::size_t bodies = immovable.size();
  first_.assign(bodies + 1, 0);
  for (const auto& [a, b] : contacts) {
    ++first_[a + 1];
    ++first_[b + 1];
  }
  for (std::size_t i = 0; i < bodies; ++i) first_[i + 1] += first_[i];
  resize_buffer(neighbours_, first_[bodies]);
  filled_.assign(first_.begin(), first_.end() - 1);
  for (const auto& [a, b] : contacts) {
    neighbours_[filled_[a]++] = b;
    neighbours_[filled_[b]++] = a;
  }

  // Breadth first from every immovable body at once.
  level_.assign(bodies, kUnsupported);
  queue_.clear();
  for (std::uint32_t i = 0; i < bodies; ++i) {
    if (immovable[i] != 0) {
      level_[i] = 0;
      queue_.push_back(i);
    }
  }
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const std::uint32_t body = queue_[head];
    for (std::uint32_t k = first_[body]; k < first_[body + 1]; ++k) {
      const std::uint32_t next = neighbours_[k];
      if (level_[next] != kUnsupported) continue;
      level_[next] = level_[body] + 1;
      queue_.push_back(next);
    }
  }
  return level_;
}

}  // namespace sphys
