#include "dynamics/constraint_colouring.h"

#include "core/buffers.h"

namespace sphys {

bool ConstraintColouring::taken(std::uint32_t colour, std::uint32_t slot) const {
  return ((bodies_[colour * words_ + slot / 64] >> (slot % 64)) & 1u) != 0;
}

void ConstraintColouring::take(std::uint32_t colour, std::uint32_t slot) {
  bodies_[colour * words_ + slot / 64] |= std::uint64_t{1} << (slot % 64);
}

void ConstraintColouring::colour(std::span<const ManifoldBodies> manifolds, std::size_t slots,
                                 std::vector<std::uint32_t>& colours) {
  words_ = (slots + 63) / 64;
  fill_buffer(bodies_, kColours * words_, std::uint64_t{0});
  resize_buffer(colours, manifolds.size());
  const auto colour_one = [&](const ManifoldBodies& m) {
    for (std::uint32_t c = 0; c < kColours; ++c) {
      if ((m.a_moves && taken(c, m.a)) || (m.b_moves && taken(c, m.b))) continue;
      if (m.a_moves) take(c, m.a);
      if (m.b_moves) take(c, m.b);
      return c;
    }
    return kOverflowColour;
  };
  for (std::size_t k = 0; k < manifolds.size(); ++k) {
    const ManifoldBodies& m = manifolds[k];
    if (!m.a_moves || !m.b_moves) colours[k] = colour_one(m);
  }
  for (std::size_t k = 0; k < manifolds.size(); ++k) {
    const ManifoldBodies& m = manifolds[k];
    if (m.a_moves && m.b_moves) colours[k] = colour_one(m);
  }
}

}  // namespace sphys
