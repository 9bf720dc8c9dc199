#include "world/joint_store.h"

namespace sphys {

void JointStore::joints_on(std::uint32_t body, std::vector<std::uint32_t>& out) const {
  const std::span<const JointModel> joints = all();
  for (std::uint32_t j = 0; j < joints.size(); ++j) {
    const JointModel& joint = joints[j];
    if (joint.alive && (joint.body_a == body || joint.body_b == body)) out.push_back(j);
  }
}

std::vector<JointStore::BodyPair> JointStore::joined_pairs(bool unpaired_only) const {
  std::vector<BodyPair> pairs;
  for (const JointModel& joint : all()) {
    if (!joint.alive || joint.body_a == kWorldSlot || joint.body_b == kWorldSlot) continue;
    if (unpaired_only && joint.desc.collide_connected) continue;
    pairs.emplace_back(joint.body_a, joint.body_b);
  }
  return pairs;
}

}  // namespace sphys
