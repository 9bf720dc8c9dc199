#include "world/joint_store.h"

namespace sphys {

JointId JointStore::add(const JointModel& model) {
  std::uint32_t slot = 0;
  if (free_.empty()) {
    slot = static_cast<std::uint32_t>(models_.size());
    models_.emplace_back();
    generation_.push_back(0);
  } else {
    slot = free_.back();
    free_.pop_back();
  }
  models_[slot] = model;
  models_[slot].alive = true;
  ++generation_[slot];  // from 1: the null id's generation 0 names no joint
  return id_of(slot);
}

void JointStore::remove(std::uint32_t slot) {
  models_[slot].alive = false;
  free_.push_back(slot);
}

void JointStore::joints_on(std::uint32_t body, std::vector<std::uint32_t>& out) const {
  for (std::uint32_t j = 0; j < models_.size(); ++j) {
    const JointModel& joint = models_[j];
    if (joint.alive && (joint.body_a == body || joint.body_b == body)) out.push_back(j);
  }
}

std::vector<JointStore::BodyPair> JointStore::joined_pairs(bool unpaired_only) const {
  std::vector<BodyPair> pairs;
  for (const JointModel& joint : models_) {
    if (!joint.alive || joint.body_a == kWorldSlot || joint.body_b == kWorldSlot) continue;
    if (unpaired_only && joint.desc.collide_connected) continue;
    pairs.emplace_back(joint.body_a, joint.body_b);
  }
  return pairs;
}

}  // namespace sphys
