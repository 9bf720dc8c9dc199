#pragma once

// The plausible mode's second method (SolverMethod::kSoftStep): the soft step (Catto's Solver2D
// "soft step", as in Box2D v3; Bepu v2's substepping). One collision pass feeds several solver
// substeps, each of which integrates velocities, warm starts, solves the contacts once with a soft
// (spring-damper) position bias, integrates positions and relaxes the contacts once without the
// bias; restitution and the impulses kept for the next step come once at the end. Contact
// separations follow the bodies' motion within the step, so speculative contacts close their gaps
// exactly. See docs/dynamics.md.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "dynamics/contact_pairs.h"
#include "dynamics/solver_stats.h"
#include "sphys/body_store.h"
#include "sphys/collision_detector.h"
#include "sphys/contact.h"
#include "sphys/material.h"
#include "sphys/math.h"
#include "sphys/parallel.h"
#include "sphys/solver_settings.h"

namespace sphys {

class SoftStepSolver {
 public:
  // Advances the store's awake bodies by dt, in `substeps` equal substeps, under `gravity` and
  // the contacts: their velocities and poses on return are those at the end of the step. The
  // other bodies count as static. `materials[k]` is contact k's material; `memory[k]` is its warm
  // start on entry and what it leaves for the next step on return. `island_of_body[i]` names moving
  // body i's island (bodies of different islands share no contact through a moving body): islands
  // are solved on `parallel`'s threads, and the result does not depend on how many there are.
  ContactSolverStats solve(BodyStore& bodies, std::span<const std::uint32_t> island_of_body,
                           std::span<const Contact> contacts, std::span<ContactMemory> memory,
                           std::span<const PairMaterial> materials, const SolverSettings& settings,
                           const Vec3& gravity, float dt, std::uint32_t substeps,
                           const Parallel& parallel);

 private:
  // A spring-damper's effect on an impulse in one substep (Catto, "Soft Constraints", GDC 2011):
  // how much of the rigid impulse and of the accumulated one the soft impulse takes.
  struct Softness {
    float mass_scale = 1.0f;
    float impulse_scale = 0.0f;
  };
  // One contact point as the solver sees it. Slot `ground` (the last) is the ground plane's.
  struct Constraint {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    Vec3 ra = Vec3::Zero();  // contact point from each centre of mass at the step's start. unit: m
    Vec3 rb = Vec3::Zero();
    Vec3 normal = Vec3::UnitY();  // from a to b
    Vec3 tangent1 = Vec3::UnitX();
    Vec3 tangent2 = Vec3::UnitZ();
    // Per direction (normal, tangent1, tangent2): the angular parts of its Jacobian (r × d) and
    // each body's inverse world inertia times them.
    struct Row {
      Vec3 ra_cross = Vec3::Zero();
      Vec3 rb_cross = Vec3::Zero();
      Vec3 turn_a = Vec3::Zero();
      Vec3 turn_b = Vec3::Zero();
      float mass = 0.0f;  // 1 / (inverse effective mass along the direction). unit: kg
    };
    std::array<Row, 3> rows{};
    // Separation at the step's start less the anchors' offset along the normal, so that adding
    // the anchors' current offset gives the current separation. unit: m
    float base_separation = 0.0f;
    // Relative normal speed before the step, then the most negative met before a solve pass
    // (the impact speed), for restitution. unit: m/s
    float approach = 0.0f;
    float friction = 0.0f;
    float restitution = 0.0f;
    bool a_moves = false;  // the body has mass here (neither static nor asleep nor the ground)
    bool b_moves = false;
    Softness soft;           // of the solve passes, for a penetrating contact
    float bias_rate = 0.0f;  // push-out speed per metre of penetration. unit: 1/s
    // Accumulated impulses of the current substep, kept across substeps. unit: N·s
    float normal_impulse = 0.0f;
    float tangent1_impulse = 0.0f;
    float tangent2_impulse = 0.0f;
    float max_normal_impulse = 0.0f;  // over the step: did the contact push at all
    // The body pair's rolling resistance (contact_pairs.h), done from one of its constraints.
    std::uint32_t pair = kNoRollingPair;
    bool rolls = false;
    std::uint32_t contact = 0;  // its index in the contacts given to solve()
  };

  void load_bodies(const BodyStore& bodies);
  void prepare(std::span<const Contact> contacts, std::span<const ContactMemory> memory,
               std::span<const PairMaterial> materials, const SolverSettings& settings,
               float substep, ContactSolverStats& stats);
  void group_islands(std::span<const std::uint32_t> island_of_body);
  // The whole step of one island: its moving bodies and its constraints (indices, in order).
  // Returns the number of bounces.
  [[nodiscard]] std::uint32_t step_island(std::span<const std::uint32_t> island_bodies,
                                          std::span<const std::uint32_t> island_constraints,
                                          BodyStore& bodies, const SolverSettings& settings,
                                          const Vec3& gravity, float substep,
                                          std::uint32_t substeps);
  void integrate_velocities(std::span<const std::uint32_t> island_bodies, const Vec3& gravity,
                            float substep);
  void warm_start(std::span<const std::uint32_t> island) const;
  void solve_contacts(std::span<const std::uint32_t> island, const SolverSettings& settings,
                      float substep, bool use_bias);
  void integrate_positions(std::span<const std::uint32_t> island_bodies, BodyStore& bodies,
                           float substep);
  [[nodiscard]] std::uint32_t restitute(std::span<const std::uint32_t> island,
                                        const SolverSettings& settings);
  void keep_impulses(std::span<ContactMemory> memory) const;
  // The relative speed of c's bodies at the contact along row `row`'s direction. unit: m/s
  [[nodiscard]] float row_speed(const Constraint& c, std::size_t row, const Vec3& direction) const;
  // Applies impulses along the normal and the two tangents at the contact (from a to b).
  void push(const Constraint& c, float normal, float tangent1, float tangent2) const;

  std::vector<Constraint> constraints_;
  std::vector<RollingPair> rolling_pairs_;
  // Per body, and one more slot at the end for the ground plane. Velocities are written only for
  // moving bodies, each by the one thread that solves its island.
  mutable std::vector<Vec3> linear_;
  mutable std::vector<Vec3> angular_;
  std::vector<Vec3> position_;  // at the step's start. unit: m
  std::vector<Quat> rotation_;  // at the step's start
  std::vector<float> inverse_mass_;
  std::vector<Mat3> inverse_inertia_;  // world frame, at the step's start
  // The motion since the step's start: translation and rotation (as a matrix, for the anchors).
  std::vector<Vec3> moved_;
  std::vector<Mat3> turned_;
  // The springs' a2 = h ω (2ζ + h ω) (dimensionless) and bias speed per metre of penetration
  // (unit: 1/s), between two moving bodies and against an immovable one.
  float spring_moving_ = 0.0f;
  float spring_immovable_ = 0.0f;
  float bias_rate_moving_ = 0.0f;
  float bias_rate_immovable_ = 0.0f;
  // Islands: island i's constraints are island_constraints_[constraint_begin_[i], ...[i+1]), its
  // bodies island_bodies_[body_begin_[i], body_begin_[i+1]).
  std::vector<std::uint32_t> island_constraints_;
  std::vector<std::uint32_t> constraint_begin_;
  std::vector<std::uint32_t> island_bodies_;
  std::vector<std::uint32_t> body_begin_;
  std::vector<std::uint32_t> island_number_;  // per island name given, its number here
  std::vector<std::uint32_t> island_bounces_;
  // The substep length the kept impulses were solved with: they are rescaled to a new one, as an
  // impulse per substep grows with its length. unit: s
  float kept_substep_ = 0.0f;
};

}  // namespace sphys
