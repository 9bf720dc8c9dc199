#pragma once

// The world's joints: a slot per joint with its generation (as the body store's), each holding
// the joint's model for the solver (dynamics/joint_model.h), and what the rest of the world asks
// of them: the joints on a body, and the body pairs they join.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dynamics/joint_model.h"
#include "sphys/joint.h"

namespace sphys {

class JointStore {
 public:
  using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

  // Takes a free slot (the most recently freed first) for `model`, alive from now on.
  JointId add(const JointModel& model);
  void remove(std::uint32_t slot);
  // True for a joint in the world; false for a stale or unknown id, or the null one.
  [[nodiscard]] bool alive(JointId id) const {
    return id.index < models_.size() && generation_[id.index] == id.generation &&
           models_[id.index].alive;
  }
  [[nodiscard]] JointId id_of(std::uint32_t slot) const { return {slot, generation_[slot]}; }
  [[nodiscard]] JointModel& at(std::uint32_t slot) { return models_[slot]; }
  [[nodiscard]] const JointModel& at(std::uint32_t slot) const { return models_[slot]; }
  // Every slot's model, dead ones included (JointModel::alive), for the solver.
  [[nodiscard]] std::span<JointModel> models() { return models_; }
  // Appends the slots of the live joints on a body slot.
  void joints_on(std::uint32_t body, std::vector<std::uint32_t>& out) const;
  // The body pairs of the live joints between two bodies (not the world): all of them, or those
  // whose bodies' contacts with each other do not count (JointDesc::collide_connected off).
  [[nodiscard]] std::vector<BodyPair> joined_pairs(bool unpaired_only) const;

 private:
  std::vector<JointModel> models_;
  std::vector<std::uint32_t> generation_;
  std::vector<std::uint32_t> free_;
};

}  // namespace sphys
