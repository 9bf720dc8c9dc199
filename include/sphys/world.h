#pragma once

// A world of rigid bodies with sphere-trees, stepped by the pipeline of its response mode
// (docs/architecture.md): collision passes of detection and response.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "sphys/body_id.h"
#include "sphys/body_store.h"
#include "sphys/collision_settings.h"
#include "sphys/contact.h"
#include "sphys/joint.h"
#include "sphys/material.h"
#include "sphys/rigid_body.h"
#include "sphys/robot_world.h"
#include "sphys/solver_settings.h"
#include "sphys/sphere_tree.h"
#include "sphys/step_stats.h"

namespace sphys {

// How contacts change velocities.
enum class ResponseMode {
  // The paper's §4: per contact, in order, the impulse magnitude of eq. 4 along the normal when
  // the contact approaches; no friction. See docs/experiment.md.
  kPaper,
  // The soft step with warm starting, Coulomb friction, rolling resistance, restitution above a
  // threshold, speculative contacts and sleeping. See docs/dynamics.md.
  kPlausible,
};

// Bodies at rest stop being simulated until something touches them (plausible mode).
struct SleepSettings {
  bool enabled = true;  // false simulates every body in every step
  // A body is still while its fastest point (|v| + |ω| · its bounding radius) is under this.
  // unit: m/s
  float speed = 0.05f;
  // A body sleeps once it and every moving body it touches have been still this long, twice
  // this long while a body of its island is not (a restless body keeps only its neighbours
  // awake). unit: s
  float time = 0.5f;
};

// Everything a world is made with, each setting declared once in the settings table
// (sphys/settings_table.h), which checks them; a default one is a valid world.
struct WorldSettings {
  Vec3 gravity = Vec3(0.0f, -9.81f, 0.0f);           // unit: m/s²
  ResponseMode response = ResponseMode::kPlausible;  // the step's pipeline (ResponseMode)
  // Paper mode: passes over the contacts at most per collision pass; the response stops early
  // after a pass that finds no approaching contact. 1 is a single pass. See docs/experiment.md.
  // unit: passes
  std::uint32_t paper_passes = 1;
  SolverSettings solver;  // plausible mode's soft step and the contacts it is given
  SleepSettings sleep;    // plausible mode
  // Collision passes: each step(dt) runs detection and response at least this many times, each
  // pass over dt / collision_passes (the solver's own substeps are solver.soft_substeps). 1..64;
  // unit: collision passes
  std::uint32_t collision_passes = 1;
  // Plausible mode: more collision passes in a step where bodies move fast, up to this many, so
  // that no moving body's fastest point (|v| + |ω| · its bounding radius) travels more than
  // `collision_pass_travel` of its bounding radius in one. Speculative contacts see straight
  // motion only; a body spinning through a pile meets contacts they did not foresee. 1..64; at
  // most `collision_passes` turns it off. unit: collision passes
  std::uint32_t max_collision_passes = 8;
  float collision_pass_travel = 0.3f;  // unit: bounding radii per collision pass, > 0
  // What detection uses of the trees, its budgets and the ground plane. Which contacts it makes
  // is the solver's (`solver`: margin, speculative contacts, manifolds); paper mode makes them
  // from overlaps only, as the paper does.
  CollisionSettings collision;
  // Unset: the paper's one Sweep & Prune in paper mode, Sweep & Prune per cell in plausible mode.
  // Both give the same pairs in the same order, so the choice changes the speed of a step, never
  // its result.
  std::optional<BroadPhaseKind> broad_phase = std::nullopt;
  // Material of the exact ground plane (CollisionSettings::ground_plane_height), if there is one.
  float ground_restitution = 0.3f;
  float ground_friction = 0.5f;  // Coulomb coefficient. unit: dimensionless, >= 0
  // Threads a step runs on (oneTBB): the broad phase's cells, the narrow phase, the contacts and
  // the solver's set-up and passes (docs/performance.md).
  // 0 takes every hardware thread. The results are bit for bit the same whatever the count.
  std::uint32_t threads = 1;
  // StepStats' plausibility figures (penetration of the leaf pairs, kinetic energy, bodies at
  // rest, jitter): each a pass over every leaf pair or body, so computed only when asked for.
  // Times and counts are always measured.
  bool plausibility_figures = false;
};

// What add_body needs. The sphere-tree and the inertia are in the body frame, whose origin is the
// centre of mass.
struct BodyDesc {
  std::shared_ptr<const SphereTree> tree;  // required, not empty; bodies of one shape may share it
  Transform pose;                          // unit: m
  Vec3 linear_velocity = Vec3::Zero();     // unit: m/s
  Vec3 angular_velocity = Vec3::Zero();    // world frame. unit: rad/s
  float mass = 1.0f;                       // ignored for static bodies. unit: kg
  Mat3 inertia = Mat3::Identity();         // about the centre of mass, body axes. unit: kg·m²
  float restitution = 0.3f;                // 0..1
  float friction = 0.5f;                   // >= 0
  bool is_static = false;                  // never moves: infinite mass, no velocities
};

class WorldAccess;
struct WorldState;
struct RobotModel;

// One world may be called from any thread, one call at a time: calls that overlap throw
// sphys::Error ("... the world is being stepped on another thread ...") rather than race, whatever
// they are, while a step, a change (add, remove, velocities, impulses, materials, budgets) or a
// read is under way (docs/reliability.md). Reads may overlap reads. A call takes its turn only for
// its own duration: a reference it returns (bodies(), contacts(), stats(), ...) is read safely
// while a Reading is held, or on the thread that steps.
class World {
 public:
  // An empty world. Throws sphys::Error for a setting outside its range (check_world_settings)
  // or lanes this processor or build lacks (resolve_solver_lanes).
  explicit World(const WorldSettings& settings = {});
  ~World();
  // Takes the other's bodies and state whole; the moved-from world may only be destroyed or
  // assigned to.
  World(World&&) noexcept;
  // As the move constructor.
  World& operator=(World&&) noexcept;

  // Holds the world for reading across several calls, e.g. while another thread copies bodies()
  // row by row: until it goes, a step or change on any thread throws sphys::Error. Making one
  // throws sphys::Error while a step or change is under way.
  class Reading {
   public:
    // Holds `world` for reading until destroyed.
    explicit Reading(const World& world);
    ~Reading();
    Reading(const Reading&) = delete;
    Reading& operator=(const Reading&) = delete;

   private:
    WorldAccess* access_;
  };

  // Throws sphys::Error naming what is wrong: no tree, a non-finite pose or velocity, a rotation
  // that is not a unit quaternion (within 1e-3), a mass that is not positive and finite, an
  // inertia that is not symmetric positive definite, restitution outside 0..1, negative friction.
  BodyId add_body(const BodyDesc& desc);
  // The body leaves the world with its contacts, pair materials, sleep and joints (listed by
  // joints_removed()); the sleeping bodies it touched or was joined to wake. Its id, and every copy
  // of it, is stale from then on. Every call taking a BodyId throws sphys::Error for a stale or
  // unknown id, or the null one (BodyId{}), and remove_body for a robot's link (remove_robot).
  void remove_body(BodyId body);
  // A copy of the body's state and mass properties.
  [[nodiscard]] RigidBody body(BodyId body) const;
  // The body's sphere-tree, in the body frame.
  [[nodiscard]] const SphereTree& tree(BodyId body) const;
  // Changes a body's velocities (e.g. a shot); the pose stays; a sleeping body wakes, and the
  // sleeping bodies it touches wake as it moves them. Non-finite values throw.
  void set_velocity(BodyId body, const Vec3& linear, const Vec3& angular);
  // Applies an impulse (unit: N·s, world frame) at a world point (unit: m) and wakes the body.
  void apply_impulse(BodyId body, const Vec3& impulse, const Vec3& point);
  // Applies a force (unit: N, world frame) at a world point (unit: m) through the next step, in
  // each of its collision passes as gravity acts, and wakes the body; forces add up until the step,
  // which ends them (apply it before every step for a lasting push). Non-finite values throw; a
  // static body takes none.
  void apply_force(BodyId body, const Vec3& force, const Vec3& point);
  // A torque (unit: N·m, world frame) through the next step, as apply_force.
  void apply_torque(BodyId body, const Vec3& torque);
  // The friction and restitution of contacts between these two bodies, instead of the mix of
  // their own (see sphys/material.h). Checked like a body's material.
  void set_pair_material(BodyId a, BodyId b, const PairMaterial& material);
  // True while the body sleeps (plausible mode); a static body never does.
  [[nodiscard]] bool asleep(BodyId body) const;
  // Body slots, alive or removed; id_of(i) is the id of slot i's body (or of its last one).
  [[nodiscard]] std::uint32_t body_slots() const;
  // Throws sphys::Error for a slot the world never had.
  [[nodiscard]] BodyId id_of(std::uint32_t slot) const;
  // True for the id of a body in the world, false for a stale or unknown one or the null one.
  [[nodiscard]] bool alive(BodyId body) const;
  // The slot of a body in the world (its row in bodies()); throws sphys::Error for a stale,
  // unknown or null id.
  [[nodiscard]] std::uint32_t slot_of(BodyId body) const;

  // Joins two bodies, or a body and the world (a null BodyId), by a joint solved with the
  // contacts (plausible mode; sphys/joint.h, docs/joints.md). Its bodies wake, and by default no
  // longer collide with each other. Throws sphys::Error naming the joint and the field for a
  // body that is not in the world, the same body twice, a zero axis, a value that is not finite,
  // limits out of order, a negative most effort, frequency or damping, or a paper-mode world.
  JointId add_joint(const JointDesc& desc);
  // The joint leaves the world and its bodies wake; its id is stale from then on. Every call
  // taking a JointId throws sphys::Error for a stale or unknown id, or the null one (JointId{}).
  void remove_joint(JointId joint);
  // True for the id of a joint in the world, false for a stale or unknown one or the null one.
  [[nodiscard]] bool joint_alive(JointId joint) const;
  // The joint as added, with the changes of the setters below.
  [[nodiscard]] JointDesc joint(JointId joint) const;
  // What the joint did in the last step that solved it: its position, speed, gap, force and
  // torque.
  [[nodiscard]] JointState joint_state(JointId joint) const;
  // The joint's motor from the next step on; its bodies wake. Checked as add_joint checks it.
  void set_joint_motor(JointId joint, const JointMotor& motor);
  // The joint's limits from the next step on, as set_joint_motor.
  void set_joint_limit(JointId joint, const JointLimit& limit);
  // The joint's spring from the next step on, as set_joint_motor.
  void set_joint_spring(JointId joint, const JointSpring& spring);
  // The joints the last remove_body removed with its body (stale ids now), in slot order.
  [[nodiscard]] std::span<const JointId> joints_removed() const;

  // Adds a robot (plausible mode; docs/robots.md): one body per link a joint moves, carrying the
  // links fixed to it, with the links' masses, centres and inertias and their spheres as its
  // tree; one joint per moving joint with the model's limits; the root link's body static at
  // `base` (kFixed) or free. Joined links and the model's allowed_link_pairs do not collide; all
  // other pairs do. It stands with every joint at 0 (or at the limit nearest 0), limp (torque
  // control, no torque). Made by add_body and add_joint calls (not one change: another thread
  // may call between them). Throws sphys::Error naming the link for a moving link with no mass
  // or no spheres, and as check_robot_model for a bad model.
  RobotId add_robot(const RobotModel& model, const Transform& base,
                    RobotBase base_kind = RobotBase::kFixed);
  // The robot's bodies and joints leave the world; its id is stale from then on. Every call
  // taking a RobotId throws sphys::Error for a stale or unknown id, or the null one.
  void remove_robot(RobotId robot);
  // True for the id of a robot in the world.
  [[nodiscard]] bool robot_alive(RobotId robot) const;
  // The robot's bodies: the root link's first, then the link of each model joint in joint order.
  [[nodiscard]] std::span<const BodyId> robot_bodies(RobotId robot) const;
  // The robot's joints, one per model joint, in joint order.
  [[nodiscard]] std::span<const JointId> robot_joints(RobotId robot) const;
  // The model the robot was added with (its base at `base`).
  [[nodiscard]] const RobotModel& robot_model(RobotId robot) const;
  // Every joint's control from the next step on (one per model joint); its bodies wake. Throws
  // sphys::Error naming the joint for another count, a value that is not finite or a
  // max_effort that is not positive.
  void set_robot_controls(RobotId robot, std::span<const RobotJointControl> controls);
  // Puts the links where the joint values place them (one per joint, within the limits), the
  // root where it is, every link at rest: a reset. Throws sphys::Error as robot_link_poses.
  void set_robot_configuration(RobotId robot, std::span<const double> values);
  // The joints' positions, speeds and efforts (RobotJointStates).
  [[nodiscard]] RobotJointStates robot_joint_states(RobotId robot) const;
  // Every link's pose in the world (the model's links' order), from its body's. unit: m
  [[nodiscard]] std::vector<Eigen::Isometry3d> robot_link_poses_in_world(RobotId robot) const;

  // Advances the world by dt (unit: s, positive and finite, else sphys::Error). Never throws
  // otherwise, but for a call on another thread under way (see above); when a body's state stops
  // being finite the step reports it in StepStats::non_finite_body and the world stays stopped
  // (later steps do nothing).
  const StepStats& step(float dt);
  // The figures of the last step (what step() returned); a default StepStats before the first.
  [[nodiscard]] const StepStats& stats() const;
  // The contacts the last step (its last collision pass) responded to: after reduction, when
  // reduced.
  [[nodiscard]] std::span<const Contact> contacts() const;
  // True once a step found a body's state not finite (StepStats::non_finite_body): later steps do
  // nothing.
  [[nodiscard]] bool stopped() const;

  // The time-critical narrow phase's budgets (CollisionSettings::max_sphere_tests and
  // max_microseconds) from the next step on, e.g. from a viewer's slider; 0 turns one off. A time
  // that is negative or not finite throws sphys::Error.
  void set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds);

  // The settings the world was made with, with the budgets set_detection_budget changed since.
  [[nodiscard]] const WorldSettings& settings() const;
  // The lanes settings().solver.lanes resolved to on this processor (never kAuto).
  [[nodiscard]] SolverLanes solver_lanes() const;
  // The box the broad phase keeps for the body (CollisionSettings::bounds_level), as of the last
  // detection.
  [[nodiscard]] Aabb bounds(BodyId body) const;
  // Every body's state by slot (id_of(slot) names it), e.g. all poses as one array.
  [[nodiscard]] const BodyStore& bodies() const;
  // The body's sphere-tree, shared: it outlives the body's removal while a holder keeps it.
  [[nodiscard]] std::shared_ptr<const SphereTree> shared_tree(BodyId body) const;

 private:
  // The bodies, the detector, the solver, sleep and the pipeline of the world's mode, with the
  // step's stages and their buffers: private to the library (src/world/world_state.h), and on the
  // heap, so that a world moves whole and a change of a stage recompiles no user.
  std::unique_ptr<WorldState> state_;
};

}  // namespace sphys
