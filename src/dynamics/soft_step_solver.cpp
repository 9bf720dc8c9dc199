#include "dynamics/soft_step_solver.h"

#include <algorithm>
#include <numbers>

#include "core/buffers.h"
#include "dynamics/contact_pairs.h"
#include "dynamics/group_by.h"
#include "dynamics/solver_bodies.h"

namespace sphys {
namespace {

// A spring stiffer than this fraction of the substep rate is not resolved by the substeps: its
// stiffness is capped there (as Box2D v3 does). unit: dimensionless
constexpr float kMostHertzPerSubstepRate = 0.125f;

// Contacts with an immovable body (the ground, a static or sleeping body) are this much stiffer:
// nothing on the other side gives way, and a pile's weight ends on them. unit: dimensionless
constexpr float kImmovableStiffness = 2.0f;

}  // namespace

// The contact spring: stiffness k = M ω² and damping c = 2 M ζ ω, solved implicitly (Catto,
// "Soft Constraints", GDC 2011). Box2D takes M as the contact's effective mass m; here M is the
// heavier body's mass (the moving one's against an immovable body), at least m. Under a load W the
// spring yields W / k: with M = m a heavy box on a light one would sink into it in proportion to
// the mass ratio, and with M its own mass only as far as a box of its weight on the ground. With
// r = m / M the impulse is −m (1/(1 + r/a2)) (v + bias) − (r/a2)/(1 + r/a2) λ, a2 = h ω (2ζ + h ω):
// r = 1 is Box2D's softness.
namespace {

float mass_of(float inverse_mass) { return inverse_mass > 0.0f ? 1.0f / inverse_mass : 0.0f; }

}  // namespace

float SoftStepSolver::row_speed(const Constraint& c, std::size_t row, const Vec3& direction) const {
  const Constraint::Row& r = c.rows[row];
  return direction.dot(linear_[c.b] - linear_[c.a]) + r.rb_cross.dot(angular_[c.b]) -
         r.ra_cross.dot(angular_[c.a]);
}

// Immovable bodies (the ground, static and sleeping ones) are shared by islands solved at once
// on other threads: their velocities, zero, are read and never written.
void SoftStepSolver::push(const Constraint& c, float normal, float tangent1, float tangent2) const {
  const Vec3 impulse = normal * c.normal + tangent1 * c.tangent1 + tangent2 * c.tangent2;
  if (c.a_moves) {
    linear_[c.a] -= inverse_mass_[c.a] * impulse;
    angular_[c.a] -=
        normal * c.rows[0].turn_a + tangent1 * c.rows[1].turn_a + tangent2 * c.rows[2].turn_a;
  }
  if (c.b_moves) {
    linear_[c.b] += inverse_mass_[c.b] * impulse;
    angular_[c.b] +=
        normal * c.rows[0].turn_b + tangent1 * c.rows[1].turn_b + tangent2 * c.rows[2].turn_b;
  }
}

void SoftStepSolver::load_bodies(const BodyStore& bodies) {
  load_solver_bodies(bodies, linear_, angular_, position_, inverse_mass_, inverse_inertia_);
  const std::size_t slots = linear_.size();
  fill_buffer(rotation_, slots, Quat(Quat::Identity()));
  fill_buffer(moved_, slots, Vec3(Vec3::Zero()));
  fill_buffer(turned_, slots, Mat3(Mat3::Identity()));
  const std::span<const Transform> poses = bodies.poses();
  for (std::size_t i = 0; i < poses.size(); ++i) rotation_[i] = poses[i].rotation;
}

void SoftStepSolver::prepare(std::span<const Contact> contacts,
                             std::span<const ContactMemory> memory,
                             std::span<const PairMaterial> materials,
                             const SolverSettings& settings, float substep,
                             ContactSolverStats& stats) {
  const auto ground = static_cast<std::uint32_t>(linear_.size() - 1);
  // Impulses were kept per substep of the last step's length; a substep of another length needs
  // them in proportion.
  const float rescale = kept_substep_ > 0.0f ? substep / kept_substep_ : 1.0f;
  constraints_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& contact = contacts[k];
    Constraint c;
    if (!place_constraint(contact, ground, inverse_mass_, position_, c)) continue;
    const float inverse_mass = inverse_mass_[c.a] + inverse_mass_[c.b];
    const std::array<Vec3, 3> directions = {c.normal, c.tangent1, c.tangent2};
    for (std::size_t r = 0; r < 3; ++r) {
      Constraint::Row& row = c.rows[r];
      row.ra_cross = c.ra.cross(directions[r]);
      row.rb_cross = c.rb.cross(directions[r]);
      row.turn_a = inverse_inertia_[c.a] * row.ra_cross;
      row.turn_b = inverse_inertia_[c.b] * row.rb_cross;
      row.mass =
          1.0f / (inverse_mass + row.ra_cross.dot(row.turn_a) + row.rb_cross.dot(row.turn_b));
    }
    const bool against_immovable = !c.a_moves || !c.b_moves;
    const float spring = against_immovable ? spring_immovable_ : spring_moving_;
    const float ratio =
        c.rows[0].mass / std::max(mass_of(inverse_mass_[c.a]), mass_of(inverse_mass_[c.b]));
    const float share = ratio / spring;
    c.soft = {1.0f / (1.0f + share), share / (1.0f + share)};
    c.bias_rate = against_immovable ? bias_rate_immovable_ : bias_rate_moving_;
    c.base_separation = -contact.depth - c.normal.dot(c.rb - c.ra);
    c.approach = row_speed(c, 0, c.normal);
    c.friction = materials[k].friction;
    c.restitution = materials[k].restitution;
    c.contact = static_cast<std::uint32_t>(k);
    const ContactMemory& kept = memory[k];
    if (settings.warm_starting && kept.solved_impulse >= 0.0f) {
      c.normal_impulse = rescale * kept.normal_impulse;
      c.tangent1_impulse = rescale * kept.friction_impulse.dot(c.tangent1);
      c.tangent2_impulse = rescale * kept.friction_impulse.dot(c.tangent2);
      ++stats.warm_started;
    }
    constraints_.push_back(c);
  }
  stats.constraints = static_cast<std::uint32_t>(constraints_.size());
  rolling_pairs_.clear();
  if (settings.rolling_resistance > 0.0f) {
    gather_rolling_pairs(constraints_, inverse_inertia_, rolling_pairs_);
  }
}

// Islands numbered by their first moving body; each lists its moving bodies and its constraints
// (each constraint in the island of a moving body of it), in order.
void SoftStepSolver::group_islands(std::span<const std::uint32_t> island_of_body) {
  const std::size_t bodies = linear_.size() - 1;  // the ground's slot is in no island
  fill_buffer(island_number_, linear_.size(), kNoGroup);
  std::uint32_t islands = 0;
  for (std::size_t i = 0; i < bodies; ++i) {
    if (inverse_mass_[i] > 0.0f && island_number_[island_of_body[i]] == kNoGroup) {
      island_number_[island_of_body[i]] = islands++;
    }
  }
  group_by(
      bodies, islands,
      [&](std::size_t i) {
        return inverse_mass_[i] > 0.0f ? island_number_[island_of_body[i]] : kNoGroup;
      },
      body_begin_, island_bodies_);
  group_by(
      constraints_.size(), islands,
      [&](std::size_t k) {
        const Constraint& c = constraints_[k];
        return island_number_[island_of_body[c.a_moves ? c.a : c.b]];
      },
      constraint_begin_, island_constraints_);
}

void SoftStepSolver::warm_start(std::span<const std::uint32_t> island) const {
  for (const std::uint32_t k : island) {
    const Constraint& c = constraints_[k];
    push(c, c.normal_impulse, c.tangent1_impulse, c.tangent2_impulse);
    if (!c.rolls) continue;
    const RollingPair& pair = rolling_pairs_[c.pair];
    if (pair.a_moves) angular_[pair.a] -= inverse_inertia_[pair.a] * pair.impulse;
    if (pair.b_moves) angular_[pair.b] += inverse_inertia_[pair.b] * pair.impulse;
  }
}

// One pass over an island's contacts. With the bias (the solve) a penetrating contact is pushed
// apart by a spring-damper; without it (the relax) the contacts only stop approaching, so that
// the push leaves no speed behind. A gap may close within the substep and no more, either way.
void SoftStepSolver::solve_contacts(std::span<const std::uint32_t> island,
                                    const SolverSettings& settings, float substep, bool use_bias) {
  const float inverse_substep = 1.0f / substep;
  for (const std::uint32_t k : island) {
    Constraint& c = constraints_[k];
    // The separation now, from the bodies' motion since the step's start (anchors carried along).
    const Vec3 moved = moved_[c.b] - moved_[c.a] + turned_[c.b] * c.rb - turned_[c.a] * c.ra;
    const float separation = c.base_separation + c.normal.dot(moved);
    float bias = 0.0f;
    float mass_scale = 1.0f;
    float impulse_scale = 0.0f;
    if (separation > 0.0f) {
      bias = separation * inverse_substep;
    } else if (use_bias) {
      // Penetration within the slop is left alone, so that resting contacts keep touching.
      const float error = std::min(separation + settings.linear_slop, 0.0f);
      bias = std::max(c.soft.mass_scale * c.bias_rate * error, -settings.max_correction_speed);
      mass_scale = c.soft.mass_scale;
      impulse_scale = c.soft.impulse_scale;
    }
    const float speed = row_speed(c, 0, c.normal);
    // The fastest approach met in the step's solve passes: a body that falls onto a contact
    // within the step meets it at the speed gravity gave it by then, not the step's start speed.
    if (use_bias) c.approach = std::min(c.approach, speed);
    const float normal_total =
        std::max(c.normal_impulse - c.rows[0].mass * (mass_scale * speed + bias) -
                     impulse_scale * c.normal_impulse,
                 0.0f);
    const float normal_change = normal_total - c.normal_impulse;
    set_normal_impulse(c, normal_total, rolling_pairs_);
    c.max_normal_impulse = std::max(c.max_normal_impulse, normal_total);

    push(c, normal_change, 0.0f, 0.0f);

    // Coulomb: the tangential impulse stays inside the disc of radius μ λn.
    float t1 = c.tangent1_impulse - c.rows[1].mass * row_speed(c, 1, c.tangent1);
    float t2 = c.tangent2_impulse - c.rows[2].mass * row_speed(c, 2, c.tangent2);
    keep_in_friction_disc(t1, t2, c.friction * c.normal_impulse);
    push(c, 0.0f, t1 - c.tangent1_impulse, t2 - c.tangent2_impulse);
    c.tangent1_impulse = t1;
    c.tangent2_impulse = t2;

    if (c.rolls) {
      resist_rolling(rolling_pairs_[c.pair], settings.rolling_resistance, angular_,
                     inverse_inertia_);
    }
  }
}

void SoftStepSolver::integrate_velocities(std::span<const std::uint32_t> island_bodies,
                                          const Vec3& gravity, float substep) {
  const Vec3 gained = gravity * substep;
  for (const std::uint32_t i : island_bodies) linear_[i] += gained;
}

// The bodies' poses by the solved velocities (rigid_body.h's integrator), and their motion since
// the step's start for the contacts' separations.
void SoftStepSolver::integrate_positions(std::span<const std::uint32_t> island_bodies,
                                         BodyStore& bodies, float substep) {
  const std::span<Transform> poses = bodies.poses();
  for (const std::uint32_t i : island_bodies) {
    // The angular velocity changes too: the angular momentum is kept as the inertia turns.
    integrate_position(poses[i], linear_[i], angular_[i], bodies.inertias_body()[i],
                       bodies.inverse_inertias_body()[i], substep);
    moved_[i] = poses[i].translation - position_[i];
    turned_[i] = (poses[i].rotation * rotation_[i].conjugate()).toRotationMatrix();
  }
}

// Restitution once the substeps are done (as Box2D does it): a contact that approached faster
// than the threshold and pushed during the step leaves at ε times that speed.
std::uint32_t SoftStepSolver::restitute(std::span<const std::uint32_t> island,
                                        const SolverSettings& settings) {
  std::uint32_t bounces = 0;
  for (const std::uint32_t k : island) {
    Constraint& c = constraints_[k];
    if (c.restitution <= 0.0f || c.max_normal_impulse <= 0.0f ||
        !(c.approach < -settings.restitution_threshold)) {
      continue;
    }
    const float target = -c.restitution * c.approach;
    const float normal_total =
        std::max(c.normal_impulse - c.rows[0].mass * (row_speed(c, 0, c.normal) - target), 0.0f);
    push(c, normal_total - c.normal_impulse, 0.0f, 0.0f);
    c.normal_impulse = normal_total;
    ++bounces;
  }
  return bounces;
}

std::uint32_t SoftStepSolver::step_island(std::span<const std::uint32_t> island_bodies,
                                          std::span<const std::uint32_t> island_constraints,
                                          BodyStore& bodies, const SolverSettings& settings,
                                          const Vec3& gravity, float substep,
                                          std::uint32_t substeps) {
  for (std::uint32_t i = 0; i < substeps; ++i) {
    integrate_velocities(island_bodies, gravity, substep);
    if (settings.warm_starting) warm_start(island_constraints);
    solve_contacts(island_constraints, settings, substep, true);
    integrate_positions(island_bodies, bodies, substep);
    solve_contacts(island_constraints, settings, substep, false);
  }
  const std::uint32_t bounces = restitute(island_constraints, settings);
  for (const std::uint32_t i : island_bodies) {
    bodies.linear_velocities()[i] = linear_[i];
    bodies.angular_velocities()[i] = angular_[i];
  }
  return bounces;
}

void SoftStepSolver::keep_impulses(std::span<ContactMemory> memory) const {
  // Contacts with no moving body were not solved: they start the next step afresh.
  for (ContactMemory& kept : memory) kept = ContactMemory{};
  for (const Constraint& c : constraints_) {
    ContactMemory& kept = memory[c.contact];
    kept.normal_impulse = c.normal_impulse;
    kept.solved_impulse = c.normal_impulse;
    kept.friction_impulse = c.tangent1_impulse * c.tangent1 + c.tangent2_impulse * c.tangent2;
  }
}

ContactSolverStats SoftStepSolver::solve(
    BodyStore& bodies, std::span<const std::uint32_t> island_of_body,
    std::span<const Contact> contacts, std::span<ContactMemory> memory,
    std::span<const PairMaterial> materials, const SolverSettings& settings, const Vec3& gravity,
    float dt, std::uint32_t substeps, const Parallel& parallel) {
  ContactSolverStats stats;
  const float substep = dt / static_cast<float>(substeps);
  const float hertz = std::min(settings.contact_hertz, kMostHertzPerSubstepRate / substep);
  const auto spring = [&](float omega, float& a2, float& bias_rate) {
    const float a1 = 2.0f * settings.contact_damping_ratio + substep * omega;
    a2 = substep * omega * a1;
    bias_rate = omega / a1;
  };
  const float omega = 2.0f * std::numbers::pi_v<float> * hertz;
  spring(omega, spring_moving_, bias_rate_moving_);
  spring(kImmovableStiffness * omega, spring_immovable_, bias_rate_immovable_);
  load_bodies(bodies);
  prepare(contacts, memory, materials, settings, substep, stats);
  group_islands(island_of_body);
  const std::size_t islands = body_begin_.size() - 1;
  fill_buffer(island_bounces_, islands, 0u);
  parallel.for_each(islands, [&](std::size_t i) {
    const std::span<const std::uint32_t> island_bodies(island_bodies_.data() + body_begin_[i],
                                                       body_begin_[i + 1] - body_begin_[i]);
    const std::span<const std::uint32_t> island_constraints(
        island_constraints_.data() + constraint_begin_[i],
        constraint_begin_[i + 1] - constraint_begin_[i]);
    island_bounces_[i] = step_island(island_bodies, island_constraints, bodies, settings, gravity,
                                     substep, substeps);
  });
  for (const std::uint32_t bounces : island_bounces_) stats.bounces += bounces;
  keep_impulses(memory);
  kept_substep_ = substep;
  return stats;
}

}  // namespace sphys
