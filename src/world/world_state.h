#pragma once

// Everything a world holds behind its public face (sphys/world.h): the one store of its bodies,
// the detector, the solver, sleep, the threads, the pipeline of its response mode and the
// buffers its stages share. Made once per world, on the heap, and never moved: the detector and
// the sleep tracker keep the store's address, the detector the threads'.

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "collision/broad_phase.h"  // pair_key: pair_materials' key, the same in either order
#include "collision/collision_detector.h"
#include "dynamics/soft_step_solver.h"
#include "sphys/body_store.h"
#include "sphys/material.h"
#include "sphys/parallel.h"
#include "sphys/step_stats.h"
#include "sphys/world.h"
#include "world/joint_store.h"
#include "world/robots_in_world.h"
#include "world/sleep_tracker.h"
#include "world/world_access.h"

namespace sphys {

struct Pipeline;

// A run of slots' share of the rest figures at the end of a step (measure_rest).
struct RestSums {
  double kinetic_energy = 0.0;  // unit: J
  double jitter = 0.0;          // the resting bodies' fastest point speeds summed. unit: m/s
  std::uint32_t at_rest = 0;    // bodies at rest (StepStats::bodies_at_rest)
  std::uint32_t resting = 0;    // bodies that should be resting, whose speeds are jitter
};

struct WorldState {
  // Throws sphys::Error for settings out of their ranges (check_world_settings).
  explicit WorldState(const WorldSettings& world_settings);
  WorldState(const WorldState&) = delete;
  WorldState& operator=(const WorldState&) = delete;

  // Wakes a sleeping body and counts it restless: a velocity, an impulse or a force set it
  // moving from outside, or a body it touched left.
  void wake(std::uint32_t body);
  // After joints or robots were added or removed: the body pairs whose contacts do not count
  // (the detector's: joined bodies, robots' allowed link pairs) and the bodies that sleep and
  // wake together (the sleep tracker's).
  void joints_changed();
  // Wakes a joint's bodies (not the world, nor a static body).
  void wake_joined(const JointModel& joint);
  // Removes the joints on a body about to leave, waking the bodies they joined, into
  // removed_joints.
  void remove_joints_on(std::uint32_t body);
  // The narrow phase's budgets from the next step on; throws sphys::Error for a time that is
  // negative or not finite, and changes nothing then.
  void set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds);

  WorldSettings settings;
  SolverLanes solver_lanes;
  // The stages of a step in this world's mode, chosen once (world/pipeline.h).
  const Pipeline* pipeline;
  // The store first: what is attached to it (detector, sleep tracker) goes before it.
  BodyStore store;
  Parallel parallel;
  CollisionDetector detector;
  SoftStepSolver solver;     // plausible mode
  SleepTracker sleep;        // plausible mode
  JointStore joints;         // plausible mode
  JointSolver joint_solver;  // solves `joints` in the soft step
  // The robots simulated (plausible mode; their joints are in `joints`), once one is added.
  std::unique_ptr<RobotsInWorld> robots;
  std::vector<JointId> removed_joints;     // by the last remove_body
  std::vector<std::uint32_t> joint_slots;  // remove_body's scratch
  std::unordered_map<std::uint64_t, PairMaterial> pair_materials;
  std::vector<PairMaterial> materials;            // per contact, plausible mode's response
  std::vector<std::uint8_t> touching;             // measure_rest's scratch, per slot
  std::vector<RestSums> rest_sums;                // measure_rest's scratch, per run of slots
  std::vector<std::uint32_t> sleep_changes;       // bodies woken or fallen asleep, scratch
  std::vector<std::uint32_t> non_finite_in_run;   // the awake loops' scratch, per run
  std::vector<std::uint32_t> removed_neighbours;  // remove_body's scratch
  StepStats stats;
  // A body's state stopped being finite: later steps do nothing.
  bool stopped = false;
  // Turns of the calls on the world (world/world_access.h).
  WorldAccess access;
};

}  // namespace sphys
