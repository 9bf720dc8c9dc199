#pragma once

// The constraint graph's colours (as Box2D v3 colours its contacts): manifolds coloured so that
// no moving body appears twice in a colour. A colour's manifolds share no velocities, so they are
// solved together, in lanes and on threads, in any order with the same result; the colours are
// solved one after another. Immovable bodies (the ground, static and sleeping bodies) are only
// read, so any number of a colour's manifolds may touch them.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sphys {

// Colours tried per manifold. A manifold that finds all of them taken by its bodies goes to the
// overflow (kOverflowColour), solved one manifold at a time after the colours.
inline constexpr std::uint32_t kColours = 24;
inline constexpr std::uint32_t kOverflowColour = kColours;

// The bodies of a manifold, by slot, and whether each moves.
struct ManifoldBodies {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  bool a_moves = false;
  bool b_moves = false;
};

class ConstraintColouring {
 public:
  // colours[k] is manifold k's colour, the first colour free for both of its moving bodies, or
  // kOverflowColour. Manifolds with an immovable body are coloured first: they take the low
  // colours, solved first in a pass, so that each pass works from the supports up. `slots`
  // bounds the bodies' slots.
  void colour(std::span<const ManifoldBodies> manifolds, std::size_t slots,
              std::vector<std::uint32_t>& colours);

 private:
  [[nodiscard]] bool taken(std::uint32_t colour, std::uint32_t slot) const;
  void take(std::uint32_t colour, std::uint32_t slot);

  std::size_t words_ = 0;              // per colour
  std::vector<std::uint64_t> bodies_;  // colour c's bodies: bits of words [c words_, (c+1) words_)
};

}  // namespace sphys
