// The world's joints through its public face: adding, removing, changing and reading them
// (sphys/joint.h). The soft step solves them (src/dynamics/joint_solver.h).

#include <string>

#include "core/id_errors.h"
#include "sphys/error.h"
#include "sphys/world.h"
#include "world/joint_checks.h"
#include "world/world_state.h"

namespace sphys {
namespace {

// A joint's body as a store slot, or kWorldSlot for the null id (the world).
std::uint32_t joint_body(const WorldState& world, const std::string& who, std::string_view field,
                         BodyId id) {
  if (id.is_null()) return kWorldSlot;
  if (!world.store.alive(id)) {
    throw Error(who + ": " + std::string(field) + ": " + not_in_world("body", id));
  }
  return id.index;
}

Transform pose_of(const WorldState& world, std::uint32_t slot) {
  return slot == kWorldSlot ? Transform{} : world.store.poses()[slot];
}

// Each body's joint frame: x along its axis, and b's turned from a's by the least rotation that
// takes a's axis to b's, so that every angle of the joint is 0 now.
void place_frames(const WorldState& world, JointModel& joint) {
  const Quat rotation_a = pose_of(world, joint.body_a).rotation;
  const Quat rotation_b = pose_of(world, joint.body_b).rotation;
  joint.frame_a = Quat::FromTwoVectors(Vec3::UnitX(), joint.desc.axis_a);
  const Quat world_a = rotation_a * joint.frame_a;
  const Quat world_b =
      Quat::FromTwoVectors(world_a * Vec3::UnitX(), rotation_b * joint.desc.axis_b) * world_a;
  joint.frame_b = (rotation_b.conjugate() * world_b).normalized();
}

// The slot of a joint in the world, for a call that holds its turn.
std::uint32_t checked_joint(const WorldState& world, JointId id) {
  return slot_named(id, world.joints.alive(id), "joint", "JointId");
}

std::string joint_name(const WorldState& world, std::uint32_t slot) {
  return "joint " + id_text(world.joints.id_of(slot)) + " (" +
         std::string(joint_type_name(world.joints.at(slot).desc.type)) + ")";
}

}  // namespace

JointId World::add_joint(const JointDesc& desc) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "add_joint");
  const std::string who = "add_joint (" + std::string(joint_type_name(desc.type)) + ")";
  if (world.settings.response != ResponseMode::kPlausible) {
    throw Error(who + ": joints are solved in plausible mode only");
  }
  check_joint_desc(who, desc);
  JointModel joint;
  joint.desc = desc;
  joint.desc.axis_a.normalize();
  joint.desc.axis_b.normalize();
  joint.body_a = joint_body(world, who, "body_a", desc.body_a);
  joint.body_b = joint_body(world, who, "body_b", desc.body_b);
  if (joint.body_a == joint.body_b) {
    throw Error(who + ": body_b: the same " +
                (joint.body_a == kWorldSlot ? std::string("world (both ids null)")
                                            : std::string("body as body_a")));
  }
  place_frames(world, joint);
  const JointId id = world.joints.add(joint);
  world.wake_joined(joint);
  world.joints_changed();
  return id;
}

void World::remove_joint(JointId id) {
  WorldState& world = *state_;
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, "remove_joint");
  const std::uint32_t slot = checked_joint(world, id);
  world.wake_joined(world.joints.at(slot));
  world.joints.remove(slot);
  world.sleep.parted();
  world.joints_changed();
}

bool World::joint_alive(JointId id) const {
  const WorldAccess::Shared turn(state_->access, "joint_alive");
  return state_->joints.alive(id);
}

JointDesc World::joint(JointId id) const {
  const WorldAccess::Shared turn(state_->access, "joint");
  return state_->joints.at(checked_joint(*state_, id)).desc;
}

JointState World::joint_state(JointId id) const {
  const WorldAccess::Shared turn(state_->access, "joint_state");
  return state_->joints.at(checked_joint(*state_, id)).state;
}

namespace {

// A setter's change to a joint, checked and made by `change(joint, who)`, its bodies woken.
template <class Change>
void change_joint(WorldState& world, JointId id, const char* call, const Change& change) {
  const WorldAccess::Alone turn(world.access, WorldAccess::Holder::kChange, call);
  const std::uint32_t slot = checked_joint(world, id);
  change(world.joints.at(slot), joint_name(world, slot));
  world.wake_joined(world.joints.at(slot));
}

}  // namespace

void World::set_joint_motor(JointId id, const JointMotor& motor) {
  change_joint(*state_, id, "set_joint_motor", [&](JointModel& joint, const std::string& who) {
    check_joint_motor(who, motor);
    joint.desc.motor = motor;
  });
}

void World::set_joint_limit(JointId id, const JointLimit& limit) {
  change_joint(*state_, id, "set_joint_limit", [&](JointModel& joint, const std::string& who) {
    check_joint_limit(who, joint.desc.type, limit);
    joint.desc.limit = limit;
  });
}

void World::set_joint_spring(JointId id, const JointSpring& spring) {
  change_joint(*state_, id, "set_joint_spring", [&](JointModel& joint, const std::string& who) {
    check_joint_spring(who, spring);
    joint.desc.spring = spring;
  });
}

std::span<const JointId> World::joints_removed() const {
  const WorldAccess::Shared turn(state_->access, "joints_removed");
  return state_->removed_joints;
}

}  // namespace sphys
