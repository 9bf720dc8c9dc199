#include "dynamics/contact_solver.h"

#include <algorithm>
#include <utility>

#include "core/buffers.h"
#include "dynamics/contact_levels.h"
#include "dynamics/contact_pairs.h"
#include "dynamics/group_by.h"
#include "dynamics/solver_bodies.h"

namespace sphys {
namespace {

// Gauss–Seidel passes over the contacts of one level in shock propagation: a level's contacts
// among themselves need a few to agree; more changes little as the velocity passes came first.
constexpr std::uint32_t kShockPasses = 4;

// A gap this small counts as touching, so that a body stopped at the surface by a gap contact
// bounces in the next step despite rounding. As a fraction of the linear slop.
constexpr float kTouchingFraction = 0.25f;

// Passes alternate forwards and backwards (symmetric Gauss–Seidel): one direction only leaves a
// bias towards the contacts met last, which tilts a stack steadily to one side.
std::uint32_t sweep_index(std::span<const std::uint32_t> island, std::uint32_t iteration,
                          std::size_t k) {
  return island[iteration % 2 == 0 ? k : island.size() - 1 - k];
}

}  // namespace

Vec3 ContactSolver::relative_velocity(const Constraint& c, const std::vector<Vec3>& linear,
                                      const std::vector<Vec3>& angular) {
  return linear[c.b] + angular[c.b].cross(c.rb) - linear[c.a] - angular[c.a].cross(c.ra);
}

// Immovable bodies (the ground, static and sleeping ones) are shared by islands solved at once
// on other threads: their velocities, zero, are read and never written.
void ContactSolver::apply(const Constraint& c, const Vec3& impulse, std::vector<Vec3>& linear,
                          std::vector<Vec3>& angular) const {
  if (c.a_moves) {
    linear[c.a] -= inverse_mass_[c.a] * impulse;
    angular[c.a] -= inverse_inertia_[c.a] * c.ra.cross(impulse);
  }
  if (c.b_moves) {
    linear[c.b] += inverse_mass_[c.b] * impulse;
    angular[c.b] += inverse_inertia_[c.b] * c.rb.cross(impulse);
  }
}

ContactSolver::PairVelocities ContactSolver::load_velocities(const Constraint& c) const {
  return {linear_[c.a], angular_[c.a], linear_[c.b], angular_[c.b]};
}

// Immovable bodies keep their zero velocities in the locals (no inverse mass, no inverse
// inertia), and are never written back.
void ContactSolver::store_velocities(const Constraint& c, const PairVelocities& v) {
  if (c.a_moves) {
    linear_[c.a] = v.linear_a;
    angular_[c.a] = v.angular_a;
  }
  if (c.b_moves) {
    linear_[c.b] = v.linear_b;
    angular_[c.b] = v.angular_b;
  }
}

float ContactSolver::row_speed(const Constraint& c, int row, const Vec3& direction,
                               const PairVelocities& v) {
  const Constraint::Row& r = c.rows[static_cast<std::size_t>(row)];
  return direction.dot(v.linear_b - v.linear_a) + r.rb_cross.dot(v.angular_b) -
         r.ra_cross.dot(v.angular_a);
}

void ContactSolver::push(const Constraint& c, int row, const Vec3& direction, float impulse,
                         PairVelocities& v) const {
  const Constraint::Row& r = c.rows[static_cast<std::size_t>(row)];
  v.linear_a -= (inverse_mass_[c.a] * impulse) * direction;
  v.angular_a -= impulse * r.turn_a;
  v.linear_b += (inverse_mass_[c.b] * impulse) * direction;
  v.angular_b += impulse * r.turn_b;
}

void ContactSolver::push_two(const Constraint& c, float impulse1, float impulse2,
                             PairVelocities& v) const {
  const Vec3 impulse = impulse1 * c.tangent1 + impulse2 * c.tangent2;
  v.linear_a -= inverse_mass_[c.a] * impulse;
  v.angular_a -= impulse1 * c.rows[1].turn_a + impulse2 * c.rows[2].turn_a;
  v.linear_b += inverse_mass_[c.b] * impulse;
  v.angular_b += impulse1 * c.rows[1].turn_b + impulse2 * c.rows[2].turn_b;
}

void ContactSolver::load_bodies(const BodyStore& bodies) {
  load_solver_bodies(bodies, linear_, angular_, position_, inverse_mass_, inverse_inertia_);
  fill_buffer(pseudo_linear_, linear_.size(), Vec3(Vec3::Zero()));
  fill_buffer(pseudo_angular_, linear_.size(), Vec3(Vec3::Zero()));
}

void ContactSolver::prepare(std::span<const Contact> contacts,
                            std::span<const ContactMemory> memory,
                            std::span<const PairMaterial> materials, const SolverSettings& settings,
                            float dt, ContactSolverStats& stats) {
  const auto ground = static_cast<std::uint32_t>(linear_.size() - 1);
  const float touching = -kTouchingFraction * settings.linear_slop;
  constraints_.clear();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& contact = contacts[k];
    Constraint c;
    if (!place_constraint(contact, ground, inverse_mass_, position_, c)) continue;
    const float inverse_mass = inverse_mass_[c.a] + inverse_mass_[c.b];
    // Fills row r for direction d and returns the effective mass along d.
    const auto row = [&](std::size_t r, const Vec3& d) {
      Constraint::Row& out = c.rows[r];
      out.ra_cross = c.ra.cross(d);
      out.rb_cross = c.rb.cross(d);
      out.turn_a = inverse_inertia_[c.a] * out.ra_cross;
      out.turn_b = inverse_inertia_[c.b] * out.rb_cross;
      const float k_inverse =
          inverse_mass + out.ra_cross.dot(out.turn_a) + out.rb_cross.dot(out.turn_b);
      return 1.0f / k_inverse;
    };
    c.normal_mass = row(0, c.normal);
    c.tangent1_mass = row(1, c.tangent1);
    c.tangent2_mass = row(2, c.tangent2);
    c.friction = materials[k].friction;
    c.restitution = materials[k].restitution;
    c.depth = contact.depth;
    // A gap may close within the step and no more; a touching contact may not approach.
    c.target_speed = contact.depth < 0.0f ? contact.depth / dt : 0.0f;
    c.approach = c.normal.dot(relative_velocity(c, linear_, angular_));
    c.contact = static_cast<std::uint32_t>(k);
    const ContactMemory& kept = memory[k];
    if (settings.warm_starting && kept.solved_impulse >= 0.0f) {
      c.normal_impulse = kept.normal_impulse;
      c.previous_solved = kept.solved_impulse;
      c.tangent1_impulse = kept.friction_impulse.dot(c.tangent1);
      c.tangent2_impulse = kept.friction_impulse.dot(c.tangent2);
      ++stats.warm_started;
    }
    // Bodies a gap contact of this pair stopped short in the last step meet now: they bounce
    // with the speed they came at, not the speed they were slowed to.
    if (c.depth >= touching) c.approach = std::min(c.approach, kept.pair_stopped_approach);
    constraints_.push_back(c);
  }
  stats.constraints = static_cast<std::uint32_t>(constraints_.size());
  rolling_pairs_.clear();
  if (settings.rolling_resistance > 0.0f) {
    gather_rolling_pairs(constraints_, inverse_inertia_, rolling_pairs_);
  }
}

void ContactSolver::solve_velocities(std::span<const std::uint32_t> island,
                                     const SolverSettings& settings) {
  if (settings.warm_starting) {
    for (const std::uint32_t k : island) {
      const Constraint& c = constraints_[k];
      apply(c,
            c.normal_impulse * c.normal + c.tangent1_impulse * c.tangent1 +
                c.tangent2_impulse * c.tangent2,
            linear_, angular_);
    }
  }
  for (std::uint32_t iteration = 0; iteration < settings.velocity_iterations; ++iteration) {
    for (std::size_t k = 0; k < island.size(); ++k) {
      const std::uint32_t index = sweep_index(island, iteration, k);
      Constraint& c = constraints_[index];
      PairVelocities v = load_velocities(c);
      // Normal first, so that friction is bounded by this pass's normal impulse.
      const float normal_speed = row_speed(c, 0, c.normal, v);
      const float normal_total =
          std::max(c.normal_impulse - c.normal_mass * (normal_speed - c.target_speed), 0.0f);
      push(c, 0, c.normal, normal_total - c.normal_impulse, v);
      set_normal_impulse(c, normal_total, rolling_pairs_);

      // Coulomb: the tangential impulse stays inside the disc of radius μ λn.
      float t1 = c.tangent1_impulse - c.tangent1_mass * row_speed(c, 1, c.tangent1, v);
      float t2 = c.tangent2_impulse - c.tangent2_mass * row_speed(c, 2, c.tangent2, v);
      keep_in_friction_disc(t1, t2, c.friction * c.normal_impulse);
      push_two(c, t1 - c.tangent1_impulse, t2 - c.tangent2_impulse, v);
      c.tangent1_impulse = t1;
      c.tangent2_impulse = t2;
      store_velocities(c, v);

      if (c.rolls) {
        resist_rolling(rolling_pairs_[c.pair], settings.rolling_resistance, angular_,
                       inverse_inertia_);
      }
    }
  }
}

// Restitution after the velocities are solved (as Box2D does it): a touching contact that
// approached faster than the threshold and took an impulse leaves at ε times that speed.
std::uint32_t ContactSolver::bounce(std::span<const std::uint32_t> island,
                                    const SolverSettings& settings) {
  const float touching = -kTouchingFraction * settings.linear_slop;
  std::uint32_t bounces = 0;
  for (const std::uint32_t k : island) {
    Constraint& c = constraints_[k];
    if (c.restitution <= 0.0f || c.depth < touching || c.normal_impulse <= 0.0f ||
        !(c.approach < -settings.restitution_threshold)) {
      continue;
    }
    const float normal_speed = c.normal.dot(relative_velocity(c, linear_, angular_));
    const float target = -c.restitution * c.approach;
    const float normal_total =
        std::max(c.normal_impulse - c.normal_mass * (normal_speed - target), 0.0f);
    apply(c, (normal_total - c.normal_impulse) * c.normal, linear_, angular_);
    c.normal_impulse = normal_total;
    ++bounces;
  }
  return bounces;
}

// Shock propagation (Guendelman, Bridson & Fedkiw 2003), after the velocity passes and the
// bounce. Sequential impulses pass a blow on through a pile one body per pass, so a body landing
// on a pile of fifty pushes the top of the pile into the rest faster than ten passes can stop.
// Here the contacts are solved level by level from what cannot move upwards, each level against
// the bodies below it held fixed: no supported contact is left approaching, whatever the pile's
// height. Only pushes are added (a contact that separates, or closes no faster than its gap
// allows, is left alone), and bodies no contact path joins to something immovable are untouched,
// so free bodies keep their momentum.
void ContactSolver::propagate_shock(std::span<const std::uint32_t> island,
                                    std::span<const std::uint32_t> level,
                                    const SolverSettings& settings) {
  // This island's slices of the shared buffers: (level of the upper body, constraint), by level.
  const std::size_t offset = static_cast<std::size_t>(island.data() - island_constraints_.data());
  std::size_t count = 0;
  for (const std::uint32_t k : island) {
    const Constraint& c = constraints_[k];
    const std::uint32_t top = std::max(level[c.a], level[c.b]);
    if (top != kUnsupported) order_[offset + count++] = {top, k};
  }
  const std::span<std::pair<std::uint32_t, std::uint32_t>> order(order_.data() + offset, count);
  std::sort(order.begin(), order.end());

  const auto share = [&](std::uint32_t body, const Vec3& r, const Vec3& n) {
    const Vec3 rn = r.cross(n);
    return inverse_mass_[body] + rn.dot(inverse_inertia_[body] * rn);
  };
  const auto push = [&](std::uint32_t body, const Vec3& r, const Vec3& impulse) {
    linear_[body] += inverse_mass_[body] * impulse;
    angular_[body] += inverse_inertia_[body] * r.cross(impulse);
  };
  // What this pass gave each contact so far, so that a later sweep may take back what an earlier
  // one gave too much (pushes at the corners of a face overshoot one by one).
  const std::span<float> given(given_.data() + offset, count);
  std::fill(given.begin(), given.end(), 0.0f);
  // Contacts struck by a blow: closing faster than shock_speed beyond their target when met.
  // Those are stopped at their target. What the velocity passes leave of a resting contact's
  // approach is let be: pushing it to zero at one corner of a face and then another only rocks
  // the body, and a stack of boxes leans.
  const std::span<std::uint8_t> struck(struck_.data() + offset, count);
  std::fill(struck.begin(), struck.end(), std::uint8_t{0});
  for (std::size_t begin = 0; begin < order.size();) {
    const std::uint32_t top = order[begin].first;
    std::size_t end = begin;
    while (end < order.size() && order[end].first == top) ++end;
    for (std::uint32_t pass = 0; pass < kShockPasses; ++pass) {
      for (std::size_t i = 0; i < end - begin; ++i) {
        const std::size_t k = pass % 2 == 0 ? begin + i : end - 1 - i;
        const Constraint& c = constraints_[order[k].second];
        const bool move_a = level[c.a] == top;
        const bool move_b = level[c.b] == top;
        const float k_inverse = (move_a ? share(c.a, c.ra, c.normal) : 0.0f) +
                                (move_b ? share(c.b, c.rb, c.normal) : 0.0f);
        if (!(k_inverse > 0.0f)) continue;
        const float normal_speed = c.normal.dot(relative_velocity(c, linear_, angular_));
        if (normal_speed < c.target_speed - settings.shock_speed) struck[k] = 1;
        if (struck[k] == 0) continue;
        const float total = std::max(given[k] + (c.target_speed - normal_speed) / k_inverse, 0.0f);
        const Vec3 impulse = (total - given[k]) * c.normal;
        given[k] = total;
        if (move_a) push(c.a, c.ra, -impulse);
        if (move_b) push(c.b, c.rb, impulse);
      }
    }
    begin = end;
  }
}

// Split impulses (Catto; Bullet): pseudo-velocities that push penetrating bodies apart by a
// fraction of the penetration beyond the slop. They move the bodies in this step only and never
// reach the real velocities, so the recovery adds no kinetic energy.
void ContactSolver::recover_penetration(std::span<const std::uint32_t> island,
                                        const SolverSettings& settings, float dt) {
  for (std::uint32_t iteration = 0; iteration < settings.position_iterations; ++iteration) {
    for (std::size_t k = 0; k < island.size(); ++k) {
      const std::uint32_t index = sweep_index(island, iteration, k);
      Constraint& c = constraints_[index];
      if (c.depth <= settings.linear_slop) continue;
      const float target =
          std::min(settings.position_correction * (c.depth - settings.linear_slop) / dt,
                   settings.max_correction_speed);
      const float speed = c.normal.dot(relative_velocity(c, pseudo_linear_, pseudo_angular_));
      const float total = std::max(c.position_impulse + c.normal_mass * (target - speed), 0.0f);
      apply(c, (total - c.position_impulse) * c.normal, pseudo_linear_, pseudo_angular_);
      c.position_impulse = total;
    }
  }
}

void ContactSolver::keep_impulses(const SolverSettings& settings, const Vec3& gravity_step,
                                  float dt, std::span<ContactMemory> memory) const {
  const float touching = -kTouchingFraction * settings.linear_slop;
  // Contacts with no moving body were not solved: they start the next step afresh.
  for (ContactMemory& kept : memory) kept = ContactMemory{};
  for (const Constraint& c : constraints_) {
    // A step starts from this step's impulse, but at most twice the last step's plus what
    // gravity adds in a step: a blow (a body landing, or what it sends down a pile) lasts one
    // step, and starting the next from it throws the pile back up faster than the passes can
    // take it back. A pile's resting impulses still build up within a few steps.
    const float before = std::max(c.previous_solved, 0.0f);
    const float start =
        std::min(c.normal_impulse, 2.0f * before + c.normal_mass * gravity_step.norm());
    const float share = c.normal_impulse > 0.0f ? start / c.normal_impulse : 0.0f;
    ContactMemory& kept = memory[c.contact];
    kept.normal_impulse = start;
    kept.solved_impulse = c.normal_impulse;
    kept.friction_impulse =
        share * (c.tangent1_impulse * c.tangent1 + c.tangent2_impulse * c.tangent2);
    // A gap contact that had to stop its bodies short: they meet in the next step, at the speed
    // they had when the gap closed. Gravity acted for the whole step but they fell only the gap,
    // a fraction of the way: the part of gravity's speed for the rest is taken back, so that the
    // bounce gains no energy.
    if (c.depth < touching && c.normal_impulse > 0.0f && c.approach < 0.0f) {
      const float used = std::min(-c.depth / (-c.approach * dt), 1.0f);
      const float moving_a = inverse_mass_[c.a] > 0.0f ? 1.0f : 0.0f;
      const float moving_b = inverse_mass_[c.b] > 0.0f ? 1.0f : 0.0f;
      const float gravity_approach = (moving_b - moving_a) * c.normal.dot(gravity_step);
      kept.stopped_approach = c.approach - (1.0f - used) * gravity_approach;
    }
  }
}

// Islands: constraints of different islands share no moving body, so each island is solved on
// its own, in the constraints' order, and the result is the same as one sweep over all of them in
// that order, whatever thread solves which island. Each constraint belongs to the island of a
// moving body of it; islands are numbered by their first constraint.
void ContactSolver::group_islands(std::span<const std::uint32_t> island_of_body) {
  fill_buffer(island_number_, linear_.size(), kNoGroup);
  std::uint32_t islands = 0;
  const auto name = [&](std::size_t k) {
    const Constraint& c = constraints_[k];
    return island_of_body[c.a_moves ? c.a : c.b];
  };
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    if (island_number_[name(k)] == kNoGroup) island_number_[name(k)] = islands++;
  }
  group_by(
      constraints_.size(), islands, [&](std::size_t k) { return island_number_[name(k)]; },
      island_begin_, island_constraints_);
}

ContactSolverStats ContactSolver::solve(BodyStore& bodies,
                                        std::span<const std::uint32_t> island_of_body,
                                        std::span<const Contact> contacts,
                                        std::span<ContactMemory> memory,
                                        std::span<const PairMaterial> materials,
                                        const SolverSettings& settings, const Vec3& gravity,
                                        float dt, const Parallel& parallel) {
  ContactSolverStats stats;
  load_bodies(bodies);
  prepare(contacts, memory, materials, settings, dt, stats);
  group_islands(island_of_body);

  std::span<const std::uint32_t> level;
  if (settings.shock_propagation) {
    const std::size_t slots = linear_.size();
    immovable_.resize(slots);
    for (std::size_t i = 0; i < slots; ++i) immovable_[i] = inverse_mass_[i] > 0.0f ? 0 : 1;
    pairs_.clear();
    for (const Constraint& c : constraints_) pairs_.emplace_back(c.a, c.b);
    level = levels_.compute(immovable_, pairs_);
    resize_buffer(order_, constraints_.size());
    resize_buffer(given_, constraints_.size());
    resize_buffer(struck_, constraints_.size());
  }
  const std::size_t islands = island_begin_.size() - 1;
  fill_buffer(island_bounces_, islands, 0u);
  parallel.for_each(islands, [&](std::size_t i) {
    const std::span<const std::uint32_t> island(island_constraints_.data() + island_begin_[i],
                                                island_begin_[i + 1] - island_begin_[i]);
    solve_velocities(island, settings);
    island_bounces_[i] = bounce(island, settings);
    if (settings.shock_propagation) propagate_shock(island, level, settings);
    recover_penetration(island, settings, dt);
  });
  for (const std::uint32_t bounces : island_bounces_) stats.bounces += bounces;
  keep_impulses(settings, gravity * dt, dt, memory);
  store_solver_velocities(linear_, angular_, bodies);
  return stats;
}

}  // namespace sphys
