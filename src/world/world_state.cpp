#include "world/world_state.h"

#include "sphys/settings_table.h"
#include "world/pipeline.h"

namespace sphys {
namespace {

// The detector's settings: the world's own, with the contacts the solver asks for in plausible
// mode and the paper's (every overlapping leaf pair, made afresh) in paper mode.
DetectorSettings detector_settings(const WorldSettings& settings) {
  DetectorSettings collision;
  static_cast<CollisionSettings&>(collision) = settings.collision;
  const bool soft_step = settings.response == ResponseMode::kPlausible;
  collision.contact_margin = soft_step ? settings.solver.contact_margin : 0.0f;
  collision.speculative = soft_step && settings.solver.speculative_contacts;
  collision.manifold_points = soft_step && settings.solver.contacts == ContactSet::kReduced
                                  ? settings.solver.manifold_points
                                  : 0;
  collision.fast_pair_reach = settings.solver.fast_pair_reach;
  // Paper mode makes every overlapping leaf pair a contact afresh, as published.
  collision.reuse_distance = soft_step ? settings.solver.reuse_distance : 0.0f;
  collision.measure_penetration = settings.plausibility_figures;
  // The same pairs either way: the paper's one Sweep & Prune for its mode, the cells (flat cost
  // per body as piles spread) for the plausible one.
  collision.broad_phase = settings.broad_phase.value_or(soft_step ? BroadPhaseKind::kCells
                                                                  : BroadPhaseKind::kSweepAndPrune);
  return collision;
}

const WorldSettings& checked(const WorldSettings& settings) {
  check_world_settings(settings);
  return settings;
}

}  // namespace

WorldState::WorldState(const WorldSettings& world_settings)
    : settings(checked(world_settings)),
      solver_lanes(resolve_solver_lanes(settings.solver.lanes)),
      pipeline(settings.response == ResponseMode::kPlausible ? &plausible_pipeline()
                                                             : &paper_pipeline()),
      parallel(settings.threads),
      detector(detector_settings(settings)),
      sleep(store) {
  solver.use_lanes(solver_lanes);
  detector.set_parallel(&parallel);
  sleep.use_threads(&parallel);
  detector.set_bodies(store);
}

void WorldState::wake(std::uint32_t body) {
  sleep_changes.clear();
  sleep.wake(body, settings.sleep, sleep_changes);
  sleep.unsettle(body);
}

void WorldState::joints_changed() {
  std::vector<JointStore::BodyPair> unpaired = joints.joined_pairs(true);
  if (robots) robots->append_unpaired(unpaired);
  detector.set_unpaired(unpaired);
  sleep.set_joined(joints.joined_pairs(false));
}

void WorldState::wake_joined(const JointModel& joint) {
  for (const std::uint32_t body : {joint.body_a, joint.body_b}) {
    if (body != kWorldSlot && !store.is_static(body)) wake(body);
  }
}

void WorldState::remove_joints_on(std::uint32_t body) {
  removed_joints.clear();
  joint_slots.clear();
  joints.joints_on(body, joint_slots);
  if (joint_slots.empty()) return;
  for (const std::uint32_t slot : joint_slots) {
    wake_joined(joints.at(slot));
    removed_joints.push_back(joints.id_of(slot));
    joints.remove(slot);
  }
  sleep.parted();
  joints_changed();
}

void WorldState::set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds) {
  WorldSettings changed = settings;
  changed.collision.max_sphere_tests = max_sphere_tests;
  changed.collision.max_microseconds = max_microseconds;
  check_world_settings(changed);
  settings = changed;
  detector.set_settings(detector_settings(settings));
}

}  // namespace sphys
