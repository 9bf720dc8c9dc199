#pragma once

// A robot's checks from joint values, as a motion planner asks them: many configurations posed
// together by float kinematics in SIMD lanes (AVX2 where the processor has it, SSE2 elsewhere,
// the same bits either way; within 1e-5 m of robot_link_poses' double) and checked against a
// world's leaf spheres by a ConfigurationChecker; and straight motions between configurations,
// their states checked coarse to fine so that a collision anywhere is found early.

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "sphys/configuration_check.h"
#include "sphys/parallel.h"
#include "sphys/robot_model.h"
#include "sphys/world_query.h"

namespace sphys {

// What a RobotChecker checks against, and how deep.
struct RobotCheckSettings {
  // Which of the world's bodies count.
  QueryFilter filter;
  // The robot's spheres against each other too, but for the model's allowed link pairs.
  bool self_collision = false;
  // Levels of the world's sphere-trees the checks answer at (ConfigurationCheckSettings's, which
  // says how): 0 the world's. unit: levels
  int tree_depth = 0;
};

// A straight motion's answer.
struct MotionResult {
  bool free = true;          // no state along the motion collides
  std::uint32_t states = 0;  // states along the motion, both ends included
  // The first colliding state along the motion (0 is the start), -1 when free, and its answer.
  std::int32_t first_collision = -1;
  ConfigurationResult collision;  // the first colliding state's answer; free when none
  // How far along the motion (0..1) the last free state before the first colliding one lies: 1
  // when free, 0 also when the start collides (then first_collision is 0).
  double last_free = 1.0;
};

// Checks a robot's configurations and straight motions, given as joint values, against a world.
class RobotChecker {
 public:
  // Throws sphys::Error for a model check_robot_model refuses, and as ConfigurationChecker does.
  RobotChecker(const WorldQuery& query, RobotModel model, RobotCheckSettings settings = {});
  ~RobotChecker();
  RobotChecker(const RobotChecker&) = delete;
  RobotChecker& operator=(const RobotChecker&) = delete;

  // Configurations the kinematics pose together: a call for a multiple of it wastes no lanes.
  static constexpr int kPosedTogether = 8;

  // The model checked, as given.
  [[nodiscard]] const RobotModel& model() const { return model_; }
  // Joint values per configuration: the model's joints.
  [[nodiscard]] std::size_t joints() const { return model_.joints.size(); }
  // "avx2", "sse2" or "portable": the kinematics' lanes on this processor.
  [[nodiscard]] const char* lanes() const;

  // `values`: N configurations of joints() joint values each (rad, m); `results`: N entries.
  // Throws sphys::Error naming the configuration and joint of the first value that is NaN,
  // infinite or outside its limits (`results` then holds some configurations' answers and not
  // others'), and for sizes that do not match. Configurations are checked on `parallel`'s
  // threads when given.
  void check(std::span<const double> values, std::span<ConfigurationResult> results,
             const Parallel* parallel = nullptr) const;

  // The robot's spheres in the world for N configurations: N × spheres × (x, y, z, radius).
  void pose_spheres(std::span<const double> values, std::span<float> spheres) const;

  // The straight motion from `from` to `to` (joints() values each): states no farther apart than
  // `resolution` (the Euclidean norm of the joint values' change, rad and m alike; > 0), both ends
  // included, checked coarse to fine (the ends, then midpoints of ever finer halves), stopping at
  // the first collision; then the states before it, in order, for the first colliding one.
  [[nodiscard]] MotionResult check_motion(std::span<const double> from, std::span<const double> to,
                                          double resolution) const;
  // N motions, from[n] to to[n], on `parallel`'s threads when given.
  void check_motions(std::span<const double> from, std::span<const double> to, double resolution,
                     std::span<MotionResult> results, const Parallel* parallel = nullptr) const;

 private:
  // The kinematics as flat float tables (robot_check.cpp) and a kernel call's buffers.
  struct Compiled;
  struct PoseScratch;
  // What one thread's call works in (robot_pose_scratch.h): posing buffers, a run of checks and a
  // motion's states, kept from one call to the next so that a warm call allocates nothing.
  struct Workspace;
  [[nodiscard]] std::unique_ptr<Workspace> take_workspace() const;
  void keep_workspace(std::unique_ptr<Workspace> workspace) const;
  // Whether each of `count` configurations' values is finite and within its joint's limits, as
  // check_joint_values checks them, without naming what is wrong: cheap enough for every call,
  // on each thread's own configurations.
  [[nodiscard]] bool within_limits(const double* values, std::size_t count) const;
  // Poses `count` (at most one kernel call's) configurations: their links' poses in `scratch`
  // and, with_spheres, their spheres, returned, else the boxes of the links with spheres.
  [[nodiscard]] const float* pose(const double* values, std::size_t count, PoseScratch& scratch,
                                  bool with_spheres = true) const;
  // The spheres of the links `checks` found near a group, placed from their links' poses in lane
  // `lane` of `links` into `spheres` (spheres × 4 floats; the others are left as they are).
  void place_near_spheres(const float* links, std::size_t lane,
                          const ConfigurationChecker::Run& checks, float* spheres) const;
  // The answer for the configuration in lane `lane` of the links' poses and boxes `workspace`
  // holds: the groups near each link's box, and the spheres of links near any placed and
  // checked.
  [[nodiscard]] ConfigurationResult check_from_links(std::size_t lane, Workspace& workspace) const;

  RobotModel model_;
  ConfigurationChecker checker_;
  std::unique_ptr<Compiled> compiled_;
  mutable std::mutex workspaces_mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> workspaces_;  // those not in use
};

}  // namespace sphys
