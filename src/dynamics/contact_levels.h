#pragma once

// Levels of a contact graph (as shock propagation, Guendelman, Bridson & Fedkiw 2003, orders
// them): what holds a body up is below it in the graph, counted in contacts from what cannot
// move.

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace sphys {

// The level of a body no path of contacts connects to an immovable one.
inline constexpr std::uint32_t kUnsupported = std::numeric_limits<std::uint32_t>::max();

// Keeps its buffers from call to call, so that a step computes levels without allocating once
// the buffers have grown to the scene.
class ContactLevels {
 public:
  // Per body: 0 when `immovable[i] != 0` (static, asleep, the ground), otherwise the fewest
  // contacts on a path to an immovable body, or kUnsupported when there is none. `contacts` are
  // pairs of body indices below immovable.size(); a contact between two immovable bodies leads
  // nowhere. The result stays valid until the next call.
  std::span<const std::uint32_t> compute(
      std::span<const std::uint8_t> immovable,
      std::span<const std::pair<std::uint32_t, std::uint32_t>> contacts);

 private:
  // The graph in compressed rows: the neighbours of body i are neighbours_[first_[i],
  // first_[i+1]).
  std::vector<std::uint32_t> first_;
  std::vector<std::uint32_t> filled_;
  std::vector<std::uint32_t> neighbours_;
  std::vector<std::uint32_t> queue_;
  std::vector<std::uint32_t> level_;
};

}  // namespace sphys
