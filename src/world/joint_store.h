#pragma once

// The world's joints: a slot per joint with its generation (core/slot_store.h), each holding
// the joint's model for the solver (dynamics/joint_model.h), and what the rest of the world asks
// of them: the joints on a body, and the body pairs they join.

#include <cstdint>
#include <utility>
#include <vector>

#include "core/slot_store.h"
#include "dynamics/joint_model.h"
#include "sphys/joint.h"

namespace sphys {

class JointStore : public SlotStore<JointId, JointModel> {
 public:
  using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

  // Appends the slots of the live joints on a body slot.
  void joints_on(std::uint32_t body, std::vector<std::uint32_t>& out) const;
  // The body pairs of the live joints between two bodies (not the world): all of them, or those
  // whose bodies' contacts with each other do not count (JointDesc::collide_connected off).
  [[nodiscard]] std::vector<BodyPair> joined_pairs(bool unpaired_only) const;
};

}  // namespace sphys
