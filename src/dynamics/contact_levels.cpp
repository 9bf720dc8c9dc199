#include "dynamics/contact_levels.h"

namespace sphys {

std::vector<std::uint32_t> contact_levels(
    std::span<const std::uint8_t> immovable,
    std::span<const std::pair<std::uint32_t, std::uint32_t>> contacts) {
  const std::size_t bodies = immovable.size();
  // The graph in compressed rows: the neighbours of body i are neighbours[first[i], first[i+1]).
  std::vector<std::uint32_t> first(bodies + 1, 0);
  for (const auto& [a, b] : contacts) {
    ++first[a + 1];
    ++first[b + 1];
  }
  for (std::size_t i = 0; i < bodies; ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> neighbours(first[bodies]);
  std::vector<std::uint32_t> filled(first.begin(), first.end() - 1);
  for (const auto& [a, b] : contacts) {
    neighbours[filled[a]++] = b;
    neighbours[filled[b]++] = a;
  }

  // Breadth first from every immovable body at once.
  std::vector<std::uint32_t> level(bodies, kUnsupported);
  std::vector<std::uint32_t> queue;
  queue.reserve(bodies);
  for (std::uint32_t i = 0; i < bodies; ++i) {
    if (immovable[i] != 0) {
      level[i] = 0;
      queue.push_back(i);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t body = queue[head];
    for (std::uint32_t k = first[body]; k < first[body + 1]; ++k) {
      const std::uint32_t next = neighbours[k];
      if (level[next] != kUnsupported) continue;
      level[next] = level[body] + 1;
      queue.push_back(next);
    }
  }
  return level;
}

}  // namespace sphys
