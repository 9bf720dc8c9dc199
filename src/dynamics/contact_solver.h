#pragma once

// The plausible mode's response: sequential impulses (Catto 2005; Box2D, Bullet, Jolt) over all
// contacts of a step, with warm starting, Coulomb friction, restitution above a threshold and
// split-impulse penetration recovery, and shock propagation through piles. See docs/dynamics.md.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "dynamics/contact_levels.h"
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

class ContactSolver {
 public:
  // Changes the velocities of the store's awake bodies so that the contacts neither
  // approach nor pull, friction stays in its cone, and contacts that approached faster than the
  // threshold bounce; the other bodies count as static. `materials[k]` is contact k's material.
  // A contact with negative depth (a gap) lets its bodies close the gap within dt and no more
  // (speculative). Afterwards position_linear()/position_angular() hold the pseudo-velocities that
  // push penetrating bodies apart: the caller moves the bodies by them for dt and forgets them,
  // so the recovery adds no kinetic energy. `gravity` is what the moving bodies were accelerated
  // by in this step before the call (it sets the speed a bounce starts from). Islands are solved
  // on `parallel`'s threads; the result does not depend on how many there are.
  // `island_of_body[i]` names moving body i's island: bodies of different islands share no
  // contact through a moving body (a coarser grouping, joined through immovable bodies too, gives
  // the same result). `memory[k]` is contact k's warm start on entry and what it leaves for the
  // next step on return.
  ContactSolverStats solve(BodyStore& bodies, std::span<const std::uint32_t> island_of_body,
                           std::span<const Contact> contacts, std::span<ContactMemory> memory,
                           std::span<const PairMaterial> materials, const SolverSettings& settings,
                           const Vec3& gravity, float dt, const Parallel& parallel);

  [[nodiscard]] std::span<const Vec3> position_linear() const { return pseudo_linear_; }
  [[nodiscard]] std::span<const Vec3> position_angular() const { return pseudo_angular_; }

 private:
  // One contact as the solver sees it. Index `ground` stands for the ground plane's slot.
  struct Constraint {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    Vec3 ra = Vec3::Zero();  // contact point from each centre of mass. unit: m
    Vec3 rb = Vec3::Zero();
    Vec3 normal = Vec3::UnitY();
    bool a_moves = false;  // the body has mass here (neither static nor asleep nor the ground)
    bool b_moves = false;
    Vec3 tangent1 = Vec3::UnitX();
    Vec3 tangent2 = Vec3::UnitZ();
    // Per direction (normal, tangent1, tangent2): the angular parts of its Jacobian (r × d) and
    // each body's inverse world inertia times them, so that the velocity passes need no matrix
    // products.
    struct Row {
      Vec3 ra_cross = Vec3::Zero();
      Vec3 rb_cross = Vec3::Zero();
      Vec3 turn_a = Vec3::Zero();
      Vec3 turn_b = Vec3::Zero();
    };
    std::array<Row, 3> rows{};
    float normal_mass = 0.0f;  // 1 / (inverse effective mass along each direction). unit: kg
    float tangent1_mass = 0.0f;
    float tangent2_mass = 0.0f;
    float friction = 0.0f;
    float restitution = 0.0f;
    // The body pair's rolling resistance (contact_pairs.h), done from one of its constraints.
    std::uint32_t pair = kNoRollingPair;
    bool rolls = false;
    float depth = 0.0f;
    float target_speed = 0.0f;  // normal speed the velocity pass aims at (≤ 0 for a gap)
    float approach = 0.0f;      // relative normal speed before the solve, for the bounce
    float normal_impulse = 0.0f;
    // The normal impulse this contact ended the last step with; negative when it is new.
    float previous_solved = -1.0f;
    float tangent1_impulse = 0.0f;
    float tangent2_impulse = 0.0f;
    float position_impulse = 0.0f;
    std::uint32_t contact = 0;  // its index in the contacts given to solve()
  };
  [[nodiscard]] static Vec3 relative_velocity(const Constraint& c, const std::vector<Vec3>& linear,
                                              const std::vector<Vec3>& angular);
  // The velocity passes' own: the two bodies' velocities held in locals while one contact is
  // solved (writes through the body arrays would each be read back by the next row, as the
  // compiler cannot tell that they do not alias), the speed along row r of c (direction d), and
  // impulses along one row or the two tangents at once.
  struct PairVelocities {
    Vec3 linear_a;
    Vec3 angular_a;
    Vec3 linear_b;
    Vec3 angular_b;
  };
  [[nodiscard]] PairVelocities load_velocities(const Constraint& c) const;
  void store_velocities(const Constraint& c, const PairVelocities& v);
  [[nodiscard]] static float row_speed(const Constraint& c, int row, const Vec3& direction,
                                       const PairVelocities& v);
  void push(const Constraint& c, int row, const Vec3& direction, float impulse,
            PairVelocities& v) const;
  void push_two(const Constraint& c, float impulse1, float impulse2, PairVelocities& v) const;
  // Applies `impulse` (world frame, from body a to body b) at the contact point.
  void apply(const Constraint& c, const Vec3& impulse, std::vector<Vec3>& linear,
             std::vector<Vec3>& angular) const;
  void load_bodies(const BodyStore& bodies);
  void prepare(std::span<const Contact> contacts, std::span<const ContactMemory> memory,
               std::span<const PairMaterial> materials, const SolverSettings& settings, float dt,
               ContactSolverStats& stats);
  void group_islands(std::span<const std::uint32_t> island_of_body);
  // The passes over one island's constraints (indices into constraints_, in order).
  void solve_velocities(std::span<const std::uint32_t> island, const SolverSettings& settings);
  [[nodiscard]] std::uint32_t bounce(std::span<const std::uint32_t> island,
                                     const SolverSettings& settings);
  void propagate_shock(std::span<const std::uint32_t> island, std::span<const std::uint32_t> level,
                       const SolverSettings& settings);
  void recover_penetration(std::span<const std::uint32_t> island, const SolverSettings& settings,
                           float dt);
  void keep_impulses(const SolverSettings& settings, const Vec3& gravity_step, float dt,
                     std::span<ContactMemory> memory) const;

  std::vector<Constraint> constraints_;
  std::vector<RollingPair> rolling_pairs_;
  // Per body, and one more slot at the end for the ground plane.
  std::vector<Vec3> linear_;
  std::vector<Vec3> angular_;
  std::vector<Vec3> position_;
  std::vector<float> inverse_mass_;
  std::vector<Mat3> inverse_inertia_;
  std::vector<Vec3> pseudo_linear_;
  std::vector<Vec3> pseudo_angular_;
  // Islands: island i's constraints are island_constraints_[island_begin_[i], island_begin_[i+1]).
  std::vector<std::uint32_t> island_constraints_;
  std::vector<std::uint32_t> island_begin_;
  std::vector<std::uint32_t> island_bounces_;
  std::vector<std::uint32_t> island_number_;  // per island name given, its number here
  // Shock propagation's buffers, kept so that a step does not allocate them anew. The last three
  // are sliced like island_constraints_, one slice per island.
  ContactLevels levels_;
  std::vector<std::uint8_t> immovable_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;  // each constraint's bodies
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order_;  // (level, constraint), sorted
  std::vector<float> given_;
  std::vector<std::uint8_t> struck_;
};

}  // namespace sphys
