#pragma once

// Levels of a contact graph for shock propagation (Guendelman, Bridson & Fedkiw 2003): what holds
// a body up is below it in the graph, counted in contacts from what cannot move.

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace sphys {

// The level of a body no path of contacts connects to an immovable one.
inline constexpr std::uint32_t kUnsupported = std::numeric_limits<std::uint32_t>::max();

// Per body: 0 when `immovable[i] != 0` (static, asleep, the ground), otherwise the fewest
// contacts on a path to an immovable body, or kUnsupported when there is none. `contacts` are
// pairs of body indices below immovable.size(); a contact between two immovable bodies leads
// nowhere.
[[nodiscard]] std::vector<std::uint32_t> contact_levels(
    std::span<const std::uint8_t> immovable,
    std::span<const std::pair<std::uint32_t, std::uint32_t>> contacts);

}  // namespace sphys
