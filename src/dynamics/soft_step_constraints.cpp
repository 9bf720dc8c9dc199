// The soft step's contacts as constraints: the bodies loaded, each contact placed and warm
// started, the supported bodies' scales from the contact graph's levels, and each constraint's
// effective mass and spring.

#include <algorithm>
#include <atomic>

#include "core/buffers.h"
#include "core/place_in_runs.h"
#include "dynamics/contact_pairs.h"
#include "dynamics/soft_step_solver.h"
#include "dynamics/solver_bodies.h"

namespace sphys {

// The contact spring: stiffness k = M ω² and damping c = 2 M ζ ω, solved implicitly (Catto,
// "Soft Constraints", GDC 2011). Box2D takes M as the contact's effective mass m; here M is the
// heavier body's mass (the moving one's against an immovable body), or the mass whose weight the
// contact carried in the last step (its warm start) if that is more. Under a load W the spring
// yields W / k: with M = m a heavy box on a light one would sink into it in proportion to the mass
// ratio, with M one body's mass the bottom of a stack of n would yield n times what the top does,
// and with the carried mass every contact under gravity yields g / ω² (0.28 mm at 30 Hz). With
// r = m / M the impulse is −m (1/(1 + r/a2)) (v + bias) − (r/a2)/(1 + r/a2) λ, a2 = h ω (2ζ + h ω):
// r = 1 is Box2D's softness.
namespace {

// A body with a resting contact deeper than this many slops (the slop and more than a resting
// contact's give under its load, g / ω² = 0.28 mm at 30 Hz) is being pushed out of an overlap: no
// static friction holds it (soft_step_blocks.cpp) until the overlap is gone. Held by its
// neighbours' static friction instead, bunnies of a 10,000-bunny heap fell asleep 1.1 to 1.5 mm
// into each other, against 0.85 mm before static friction and 0.98 mm with this. unit:
// dimensionless
constexpr float kPushedDepthPerSlop = 2.0f;

// A contact closing faster than this is not resting, however deep: a body landing on its foot
// is stopped by static friction there, not let slide. unit: m/s
constexpr float kRestingApproach = 0.05f;

// What a supporting body's inverse mass and inertia count for at most, against a body it
// carries (scale_supported()): it counts at least twice as heavy as it is. Gauss–Seidel passes
// the weight of a column of equal bodies down slowly, and a column of 20 boxes on its stiff
// springs (the load's mass) bounced at up to 0.35 m/s, drifted 17 to 26 cm sideways and never
// slept; counted twice as heavy, it sleeps within a second, 8.6 mm off. unit: dimensionless
constexpr float kSupportScale = 0.5f;

// Bodies whose centres of mass close or part faster than this are in an impact, and the lower
// keeps its own mass against the upper (as heavy as it, if lighter): counted twice as heavy, the
// bunnies of a falling stack of 20 landing on a pile went 7.1% of a bunny into each other, in
// one of seven seeds of 8 × 20, against 2.1% at most with this. unit: m/s
constexpr float kImpactSpeed = 1.0f;

float mass_of(float inverse_mass) { return inverse_mass > 0.0f ? 1.0f / inverse_mass : 0.0f; }

}  // namespace

// A body pair's contacts come one after another (the detector and the reducer emit them by
// pair). Gauss–Seidel passes a heavy body's weight down through a light one slowly, at a rate set
// by their mass ratio: a box 100 times heavier on a light one squeezed it 2 to 6 cm into the plane
// and slid off. So in a pair whose bodies both move, the supported body (fewer contacts from the
// ground, a static or a sleeping body) counts as at least as heavy as the one it carries, and at
// least twice its own mass but in an impact (kSupportScale, kImpactSpeed): its inverse mass and
// inertia are scaled in these contacts, in every pass, and the upper body is stopped in one pass
// as if its support stood on what holds it up. Bodies at the same level and piles no contact path
// ties to anything immovable keep their own masses. (Scaled by the load the pair carried instead,
// a heap's supported bunnies turned so heavy that falling ones went 19% of a bunny deep into the
// 1,000-bunny heap.)
void SoftStepSolver::find_support_levels() {
  const std::size_t slots = velocity_.size();
  fill_buffer(immovable_, slots, std::uint8_t{0});
  for (std::size_t i = 0; i < slots; ++i) immovable_[i] = inverse_mass_[i] > 0.0f ? 0 : 1;
  support_level_ = levels_.compute(immovable_, pairs_);
}

void SoftStepSolver::scale_supported(Constraint& c) const {
  c.scale_a = 1.0f;
  c.scale_b = 1.0f;
  if (!c.a_moves || !c.b_moves || support_level_[c.a] == support_level_[c.b]) return;
  const bool a_below = support_level_[c.a] < support_level_[c.b];
  const float lower = mass_of(inverse_mass_[a_below ? c.a : c.b]);
  const float upper = mass_of(inverse_mass_[a_below ? c.b : c.a]);
  // Twice as heavy but in an impact (kImpactSpeed); as heavy as what it carries always.
  const bool impact =
      (velocity_[c.b].linear - velocity_[c.a].linear).squaredNorm() > kImpactSpeed * kImpactSpeed;
  (a_below ? c.scale_a : c.scale_b) = std::min(impact ? 1.0f : kSupportScale, lower / upper);
}

void SoftStepSolver::set_masses(Constraint& c, const SoftStepContext& context) const {
  const Vec3 ra_cross = c.ra.cross(c.normal);
  const Vec3 rb_cross = c.rb.cross(c.normal);
  c.mass =
      1.0f / (c.scale_a * (inverse_mass_[c.a] + ra_cross.dot(inverse_inertia_[c.a] * ra_cross)) +
              c.scale_b * (inverse_mass_[c.b] + rb_cross.dot(inverse_inertia_[c.b] * rb_cross)));
  // The spring's mass M: the heavier body's, or the mass whose weight the contact carried in the
  // last step if more (the bottom of a stack carries the stack).
  const float spring_mass =
      std::max({mass_of(inverse_mass_[c.a]), mass_of(inverse_mass_[c.b]), c.carried});
  const bool against_immovable = !c.a_moves || !c.b_moves;
  const float spring = against_immovable ? context.spring_immovable : context.spring_moving;
  const float share = c.mass / spring_mass / spring;
  c.soft = {1.0f / (1.0f + share), share / (1.0f + share)};
}

void SoftStepSolver::load_bodies(const BodyStore& bodies, const Parallel& parallel) {
  load_solver_bodies(bodies, parallel, velocity_, position_, inverse_mass_, inverse_inertia_);
  const std::size_t slots = velocity_.size();
  resize_buffer(rotation_, slots);
  resize_buffer(motion_, slots);
  const std::span<const Transform> poses = bodies.poses();
  parallel.for_each_run(slots, kSlotsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      rotation_[i] = i < poses.size() ? poses[i].rotation : Quat::Identity();
      motion_[i] = SolverMotion{};
    }
  });
  // The forces applied for the step, on the bodies that move (a sleeping one counts as static).
  forced_ = !bodies.forced().empty();
  if (!forced_) return;
  fill_buffer(acceleration_, slots, SolverVelocity{});
  for (const std::uint32_t i : bodies.forced()) {
    acceleration_[i] = {inverse_mass_[i] * bodies.forces()[i],
                        inverse_inertia_[i] * bodies.torques()[i]};
  }
}

void SoftStepSolver::prepare(std::span<const Contact> contacts,
                             std::span<const ContactMemory> memory, const SoftStepContext& context,
                             SoftStepStats& stats) {
  const auto ground = static_cast<std::uint32_t>(velocity_.size() - 1);
  // Impulses were kept per substep of the last step's length; a substep of another length needs
  // them in proportion.
  const float substep_dt = context.substep_dt;
  const Parallel& parallel = context.parallel;
  const float rescale = kept_substep_dt_ > 0.0f ? substep_dt / kept_substep_dt_ : 1.0f;
  // The impulse that holds up a kilogram against gravity for a substep. unit: N s / kg
  const float weight_per_substep = context.gravity.norm() * substep_dt;
  const bool warm = context.warm_starting;
  // The contacts with a moving body, in order (constrained_), each then made a constraint on the
  // threads, which marks where a body pair's constraints begin.
  fill_buffer(pushed_out_, velocity_.size(), std::uint8_t{0});
  const float pushed_depth = kPushedDepthPerSlop * context.lanes.linear_slop;
  compact_in_runs(
      parallel, contacts.size(), kConstraintsPerRun,
      [&](std::size_t k) { return constrains(contacts[k], ground, inverse_mass_); },
      [&](std::size_t kept) {
        resize_buffer(constrained_, kept);
        resize_buffer(constraints_, kept);
        resize_buffer(pair_starts_, kept);
      },
      [&](std::size_t position, std::size_t k) {
        constrained_[position] = static_cast<std::uint32_t>(k);
      },
      run_first_);
  std::atomic<std::uint32_t> warm_started{0};
  parallel.for_each_run(
      constraints_.size(), kConstraintsPerRun, [&](std::size_t begin, std::size_t end) {
        std::uint32_t run_warm_started = 0;
        for (std::size_t j = begin; j < end; ++j) {
          const std::uint32_t k = constrained_[j];
          const Contact& contact = contacts[k];
          pair_starts_[j] = j == 0 || !same_pair(contacts[constrained_[j - 1]], contact) ? 1 : 0;
          Constraint c;
          place_constraint(contact, ground, inverse_mass_, position_, c);
          const ContactMemory& kept = memory[k];
          if (warm && kept.solved) {
            ++run_warm_started;
            c.normal_impulse = rescale * kept.normal_impulse;
            c.friction_impulse = rescale * kept.friction_impulse;
            c.twist_impulse = rescale * kept.twist_impulse;
            c.creep = kept.creep;
            c.stuck = kept.stuck;
          }
          c.carried = weight_per_substep > 0.0f ? c.normal_impulse / weight_per_substep : 0.0f;
          c.base_separation = -contact.depth - c.normal.dot(c.rb - c.ra);
          const SolverVelocity& va = velocity_[c.a];
          const SolverVelocity& vb = velocity_[c.b];
          c.approach =
              c.normal.dot(vb.linear + vb.angular.cross(c.rb) - va.linear - va.angular.cross(c.ra));
          c.contact = k;
          // Resting deeper than its give: its moving bodies are being pushed out of an overlap.
          // (A contact closing, as a body landing on it does, is not resting: static friction is
          // what stops it.)
          if (contact.depth > pushed_depth && c.approach > -kRestingApproach) {
            for (const std::uint32_t body : {c.a_moves ? c.a : ground, c.b_moves ? c.b : ground}) {
              if (body != ground) {
                std::atomic_ref<std::uint8_t>(pushed_out_[body])
                    .store(1, std::memory_order_relaxed);
              }
            }
          }
          constraints_[j] = c;
        }
        warm_started.fetch_add(run_warm_started, std::memory_order_relaxed);
      });
  stats.warm_started += warm_started.load();
  cut_manifolds(parallel);
  // Two serial jobs on the manifolds, neither needing the other: the support levels (for the
  // masses next) and the manifolds' colours (for the packing), side by side.
  parallel.side_by_side([&] { find_support_levels(); }, [&] { colour_manifolds(); });
  parallel.for_each_run(constraints_.size(), kConstraintsPerRun,
                        [&](std::size_t begin, std::size_t end) {
                          for (std::size_t j = begin; j < end; ++j) {
                            scale_supported(constraints_[j]);
                            set_masses(constraints_[j], context);
                          }
                        });
  stats.contacts_solved = static_cast<std::uint32_t>(constraints_.size());
}

}  // namespace sphys
