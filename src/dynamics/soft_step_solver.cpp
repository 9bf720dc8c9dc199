#include "dynamics/soft_step_solver.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/buffers.h"
#include "dynamics/constraint_colouring.h"
#include "dynamics/contact_lanes.h"
#include "dynamics/contact_pairs.h"
#include "dynamics/group_by.h"
#include "dynamics/solver_bodies.h"
#include "dynamics/tangent_basis.h"

namespace sphys {
namespace {

// A spring stiffer than this fraction of the substep rate is not resolved by the substeps: its
// stiffness is capped there (as Box2D v3 does). unit: dimensionless
constexpr float kMostHertzPerSubstepRate = 0.125f;

// Contacts with an immovable body (the ground, a static or sleeping body) are this much stiffer:
// nothing on the other side gives way, and a pile's weight ends on them. unit: dimensionless
constexpr float kImmovableStiffness = 2.0f;

// No body turns more than this in a substep (as Box2D bounds rotation): a turn that large is
// beyond what the integrator and the contacts' separations follow, and bodies squeezed between two
// 10⁹ times heavier ones were spun up to 10¹⁹ rad/s and overflowed. 283 rad/s at 60 frames of 6
// substeps a second. unit: rad
constexpr float kMostTurnPerSubstep = 0.25f * std::numbers::pi_v<float>;

// The tangent rows are solved together while their effective mass's determinant is at least this
// share of its diagonal's product, one by one where it is less (nearly singular). unit:
// dimensionless
constexpr double kLeastTangentConditioning = 1e-6;

// A manifold's normals summed to less than this length cancel out (a body wedged between
// opposite faces): friction takes the first point's normal. unit: dimensionless
constexpr float kSmallestNormalSum = 1e-3f;

// Contacts per item of the threaded loops that prepare constraints and keep their impulses.
// unit: contacts
constexpr std::size_t kConstraintsPerRun = 128;

}  // namespace

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

float mass_of(float inverse_mass) { return inverse_mass > 0.0f ? 1.0f / inverse_mass : 0.0f; }

}  // namespace

void SoftStepSolver::use_lanes(SolverLanes lanes) { kernels_ = &lane_kernels(lanes); }

// A body pair's contacts come one after another (the detector and the reducer emit them by
// pair). Gauss–Seidel passes a heavy body's weight down through a light one slowly, at a rate set
// by their mass ratio: a box 100 times heavier on a light one squeezed it 2 to 6 cm into the plane
// and slid off. So in a pair whose bodies both move, the supported body (fewer contacts from the
// ground, a static or a sleeping body) counts as at least as heavy as the one it carries: its
// inverse mass and inertia are scaled by their mass ratio in these contacts, in every pass, and
// the upper body is stopped in one pass as if its support stood on what holds it up. Bodies of one
// mass, bodies at the same level, and piles no contact path ties to anything immovable keep their
// own masses. (Scaled by the load the pair carried instead, a heap's supported bunnies turned so
// heavy that falling ones went 19% of a bunny deep into the 1,000-bunny heap.)
void SoftStepSolver::find_support_levels() {
  const std::size_t slots = velocity_.size();
  fill_buffer(immovable_, slots, std::uint8_t{0});
  for (std::size_t i = 0; i < slots; ++i) immovable_[i] = inverse_mass_[i] > 0.0f ? 0 : 1;
  pairs_.clear();
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    if (k == 0 || !same_bodies(constraints_[k], constraints_[k - 1])) {
      pairs_.emplace_back(constraints_[k].a, constraints_[k].b);
    }
  }
  support_level_ = levels_.compute(immovable_, pairs_);
}

void SoftStepSolver::scale_supported(Constraint& c) const {
  c.scale_a = 1.0f;
  c.scale_b = 1.0f;
  if (!c.a_moves || !c.b_moves || support_level_[c.a] == support_level_[c.b]) return;
  const bool a_below = support_level_[c.a] < support_level_[c.b];
  const float lower = mass_of(inverse_mass_[a_below ? c.a : c.b]);
  const float upper = mass_of(inverse_mass_[a_below ? c.b : c.a]);
  (a_below ? c.scale_a : c.scale_b) = std::min(1.0f, lower / upper);
}

void SoftStepSolver::set_masses(Constraint& c) const {
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
  const float spring = against_immovable ? spring_immovable_ : spring_moving_;
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
}

void SoftStepSolver::prepare(std::span<const Contact> contacts,
                             std::span<const ContactMemory> memory, const SolverSettings& settings,
                             const Vec3& gravity, float substep, const Parallel& parallel,
                             ContactSolverStats& stats) {
  const auto ground = static_cast<std::uint32_t>(velocity_.size() - 1);
  // Impulses were kept per substep of the last step's length; a substep of another length needs
  // them in proportion.
  const float rescale = kept_substep_ > 0.0f ? substep / kept_substep_ : 1.0f;
  // The impulse that holds up a kilogram against gravity for a substep. unit: N s / kg
  const float weight_per_substep = gravity.norm() * substep;
  const bool warm = settings.warm_starting;
  // The contacts with a moving body, in order, each named by a constraint that is then made on
  // the threads.
  resize_buffer(constraints_, contacts.size());
  std::size_t count = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (!constrains(contacts[k], ground, inverse_mass_)) continue;
    constraints_[count++].contact = static_cast<std::uint32_t>(k);
    if (warm && memory[k].solved) ++stats.warm_started;
  }
  resize_buffer(constraints_, count);
  parallel.for_each_run(
      constraints_.size(), kConstraintsPerRun, [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
          const std::uint32_t k = constraints_[j].contact;
          const Contact& contact = contacts[k];
          Constraint c;
          place_constraint(contact, ground, inverse_mass_, position_, c);
          const ContactMemory& kept = memory[k];
          if (warm && kept.solved) {
            c.normal_impulse = rescale * kept.normal_impulse;
            c.friction_impulse = rescale * kept.friction_impulse;
            c.twist_impulse = rescale * kept.twist_impulse;
          }
          c.carried = weight_per_substep > 0.0f ? c.normal_impulse / weight_per_substep : 0.0f;
          c.base_separation = -contact.depth - c.normal.dot(c.rb - c.ra);
          const SolverVelocity& va = velocity_[c.a];
          const SolverVelocity& vb = velocity_[c.b];
          c.approach =
              c.normal.dot(vb.linear + vb.angular.cross(c.rb) - va.linear - va.angular.cross(c.ra));
          c.contact = k;
          constraints_[j] = c;
        }
      });
  // Two serial jobs on the constraints as made, neither needing the other: the support levels
  // (for the masses next) and the manifolds' colours (for the packing), side by side.
  parallel.for_each(2, [&](std::size_t job) {
    if (job == 0) {
      find_support_levels();
    } else {
      colour_manifolds();
    }
  });
  parallel.for_each_run(constraints_.size(), kConstraintsPerRun,
                        [&](std::size_t begin, std::size_t end) {
                          for (std::size_t j = begin; j < end; ++j) {
                            scale_supported(constraints_[j]);
                            set_masses(constraints_[j]);
                          }
                        });
  stats.constraints = static_cast<std::uint32_t>(constraints_.size());
}

namespace {

void put(const Vec3& v, int lane, auto& lanes) {
  for (int k = 0; k < 3; ++k) lanes[k][lane] = v[k];
}
void put(const Mat3& m, int lane, auto& lanes) {
  for (int k = 0; k < 9; ++k) lanes[k][lane] = m.data()[k];
}

}  // namespace

// Lane `lane` of `block` from a manifold's constraints, and its friction at the centre of its
// points; the block was zeroed, so the points past the manifold's last stay empty.
template <int W>
void SoftStepSolver::pack_lane(std::uint32_t index, const PairMaterial& material,
                               ManifoldBlock<W>& block, int lane) const {
  const Manifold& manifold = manifolds_[index];
  const Constraint& first = constraints_[manifold.first];
  block.body_a[lane] = first.a;
  block.body_b[lane] = first.b;
  block.a_moves[lane] = first.a_moves ? 1u : 0u;
  block.b_moves[lane] = first.b_moves ? 1u : 0u;
  const float inverse_mass_a = first.scale_a * inverse_mass_[first.a];
  const float inverse_mass_b = first.scale_b * inverse_mass_[first.b];
  block.inverse_mass_a[lane] = inverse_mass_a;
  block.inverse_mass_b[lane] = inverse_mass_b;
  const Mat3 inverse_inertia_a = first.scale_a * inverse_inertia_[first.a];
  const Mat3 inverse_inertia_b = first.scale_b * inverse_inertia_[first.b];
  put(inverse_inertia_a, lane, block.inverse_inertia_a);
  put(inverse_inertia_b, lane, block.inverse_inertia_b);
  block.friction[lane] = material.friction;
  block.restitution[lane] = material.restitution;
  const bool against_immovable = !first.a_moves || !first.b_moves;
  const float bias_rate = against_immovable ? bias_rate_immovable_ : bias_rate_moving_;
  block.bias_rate[lane] = bias_rate;
  // Rolling resistance stops the bodies' relative turning: its mass is the inverse of the sum of
  // their inverse inertias. A pair with no inverse inertia at all (point masses) cannot turn.
  const Mat3 sum = inverse_inertia_a + inverse_inertia_b;
  put(inverse_or_zero(sum), lane, block.rolling_mass);

  // The points, and what friction at their centre takes from them: their mean normal and point,
  // and the friction and twist they kept.
  Vec3 normal_sum = Vec3::Zero();
  Vec3 centre_a = Vec3::Zero();
  Vec3 centre_b = Vec3::Zero();
  Vec3 friction = Vec3::Zero();
  float twist = 0.0f;
  // The points in an order that alternates sides: the first, the one farthest from it, then the
  // rest. A pass solves them one after another, each pushing until it alone stops approaching;
  // when a flat face lands on four, solving neighbours in turn tipped the body onto the last and
  // sent it back up (a box landing at 1.5 m/s left at 0.38 m/s with no restitution), and the
  // opposite corner next undoes most of the first one's tipping. (The contact reducer orders the
  // manifolds it reduces so already: a run of four or fewer is kept in the narrow phase's order.)
  std::array<std::uint32_t, kManifoldPoints> order{0, 1, 2, 3};
  if (manifold.count > 2) {
    std::uint32_t far = 1;
    float farthest = -1.0f;
    for (std::uint32_t i = 1; i < manifold.count; ++i) {
      const float d = (constraints_[manifold.first + i].ra - first.ra).squaredNorm();
      if (d > farthest) {
        farthest = d;
        far = i;
      }
    }
    std::swap(order[1], order[far]);
  }
  for (std::uint32_t i = 0; i < manifold.count; ++i) {
    const Constraint& c = constraints_[manifold.first + order[i]];
    auto& p = block.points[i];
    put(c.normal, lane, p.normal);
    put(c.ra, lane, p.ra);
    put(c.rb, lane, p.rb);
    p.mass[lane] = c.mass;
    p.mass_scale[lane] = c.soft.mass_scale;
    p.impulse_scale[lane] = c.soft.impulse_scale;
    p.base_separation[lane] = c.base_separation;
    p.approach[lane] = c.approach;
    p.impulse[lane] = c.normal_impulse;
    block.contact[i][lane] = c.contact;
    normal_sum += c.normal;
    centre_a += c.ra;
    centre_b += c.rb;
    friction += c.friction_impulse;
    twist += c.twist_impulse;
  }
  block.point_count = std::max(block.point_count, manifold.count);
  const float share_of_one = 1.0f / static_cast<float>(manifold.count);
  centre_a *= share_of_one;
  centre_b *= share_of_one;
  for (std::uint32_t i = 0; i < manifold.count; ++i) {
    block.points[i].lever[lane] = (constraints_[manifold.first + order[i]].ra - centre_a).norm();
  }
  // Normals that cancel (a body wedged between opposite faces) leave the first point's.
  const float length = normal_sum.norm();
  const Vec3 normal = length > kSmallestNormalSum ? Vec3(normal_sum / length) : first.normal;
  Vec3 tangent1;
  Vec3 tangent2;
  tangent_basis(normal, tangent1, tangent2);
  put(normal, lane, block.friction_normal);
  put(tangent1, lane, block.tangent1);
  put(centre_a, lane, block.centre_a);
  put(centre_b, lane, block.centre_b);

  // The tangent rows' effective mass K (2 × 2, symmetric, positive definite as a body moves) and
  // its inverse; the twist's about the normal.
  const Vec3 a1 = centre_a.cross(tangent1);
  const Vec3 a2 = centre_a.cross(tangent2);
  const Vec3 b1 = centre_b.cross(tangent1);
  const Vec3 b2 = centre_b.cross(tangent2);
  const float moving = inverse_mass_a + inverse_mass_b;
  const float k11 = moving + a1.dot(inverse_inertia_a * a1) + b1.dot(inverse_inertia_b * b1);
  const float k22 = moving + a2.dot(inverse_inertia_a * a2) + b2.dot(inverse_inertia_b * b2);
  const float k12 = a1.dot(inverse_inertia_a * a2) + b1.dot(inverse_inertia_b * b2);
  // In double, and only where K is far from singular: bodies 10¹⁵ times apart in mass leave a
  // determinant that float rounds to zero or to a sliver whose inverse overflows.
  const double determinant = double{k11} * k22 - double{k12} * k12;
  if (determinant > kLeastTangentConditioning * double{k11} * k22 && std::isfinite(determinant)) {
    block.tangent_mass[0][lane] = static_cast<float>(k22 / determinant);
    block.tangent_mass[1][lane] = static_cast<float>(-k12 / determinant);
    block.tangent_mass[2][lane] = static_cast<float>(k11 / determinant);
  } else {
    // Each row on its own.
    block.tangent_mass[0][lane] = k11 > 0.0f ? 1.0f / k11 : 0.0f;
    block.tangent_mass[2][lane] = k22 > 0.0f ? 1.0f / k22 : 0.0f;
  }
  const float twist_k = normal.dot(sum * normal);
  block.twist_mass[lane] = twist_k > 0.0f ? 1.0f / twist_k : 0.0f;
  block.friction_impulse[0][lane] = friction.dot(tangent1);
  block.friction_impulse[1][lane] = friction.dot(tangent2);
  block.twist_impulse[lane] = twist;
}

void SoftStepSolver::colour_manifolds() {
  // A body pair's contacts come one after another (the detector and the reducer emit them by
  // pair), cut into manifolds of at most kManifoldPoints.
  manifolds_.clear();
  manifold_bodies_.clear();
  for (std::size_t first = 0; first < constraints_.size();) {
    const Constraint& c = constraints_[first];
    std::size_t end = first + 1;
    while (end < constraints_.size() && end - first < kManifoldPoints &&
           same_bodies(constraints_[end], c)) {
      ++end;
    }
    manifolds_.push_back(
        {static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(end - first)});
    manifold_bodies_.push_back({c.a, c.b, c.a_moves, c.b_moves});
    first = end;
  }
  colouring_.colour(manifold_bodies_, velocity_.size(), colours_);
  // By colour, and within a colour by point count, most first: a block's lanes then hold
  // manifolds of one count, and no lane idles through points past its manifold's last. A
  // colour's manifolds share no moving body, so their order within it changes no result.
  group_by(
      manifolds_.size(), (kColours + 1) * kManifoldPoints,
      [&](std::size_t k) {
        return colours_[k] * kManifoldPoints + kManifoldPoints - manifolds_[k].count;
      },
      count_begin_, by_colour_);
  // Each colour's manifolds, kLaneWidth to a block; the overflow's one to a block.
  fill_buffer(block_begin_, kColours + 1, 0u);
  std::size_t blocks = 0;
  for (std::uint32_t colour = 0; colour < kColours; ++colour) {
    block_begin_[colour] = static_cast<std::uint32_t>(blocks);
    const std::size_t count = colour_first(colour + 1) - colour_first(colour);
    blocks += (count + kLaneWidth - 1) / kLaneWidth;
  }
  block_begin_[kColours] = static_cast<std::uint32_t>(blocks);
}

void SoftStepSolver::pack(std::span<const PairMaterial> materials, const Parallel& parallel) {
  const std::size_t blocks = block_begin_[kColours];
  const auto ground = static_cast<std::uint32_t>(velocity_.size() - 1);
  const auto empty = [&](auto& block) {
    block = {};
    std::fill(std::begin(block.body_a), std::end(block.body_a), ground);
    std::fill(std::begin(block.body_b), std::end(block.body_b), ground);
  };
  resize_buffer(blocks_, blocks);
  // Block b holds the manifolds of its colour from the (b - the colour's first block)-th lane's
  // worth on; each block is packed on its own, on the threads.
  parallel.for_each(blocks, [&](std::size_t b) {
    const auto colour = static_cast<std::uint32_t>(
        std::upper_bound(block_begin_.begin(), block_begin_.begin() + kColours, b) -
        block_begin_.begin() - 1);
    ManifoldBlock<kLaneWidth>& block = blocks_[b];
    empty(block);
    const std::uint32_t first =
        colour_first(colour) + (static_cast<std::uint32_t>(b) - block_begin_[colour]) * kLaneWidth;
    const std::uint32_t end = std::min(colour_first(colour + 1), first + kLaneWidth);
    for (std::uint32_t k = first; k < end; ++k) {
      const std::uint32_t manifold = by_colour_[k];
      pack_lane(manifold, materials[constraints_[manifolds_[manifold].first].contact], block,
                static_cast<int>(k - first));
    }
  });
  const std::uint32_t overflow_begin = colour_first(kOverflowColour);
  resize_buffer(overflow_, colour_first(kOverflowColour + 1) - overflow_begin);
  for (std::size_t k = 0; k < overflow_.size(); ++k) {
    empty(overflow_[k]);
    const std::uint32_t manifold = by_colour_[overflow_begin + k];
    pack_lane(manifold, materials[constraints_[manifolds_[manifold].first].contact], overflow_[k],
              0);
  }
}

LaneBodies SoftStepSolver::lane_bodies() {
  return {velocity_.data()->linear.data(), motion_.data()->moved.data()};
}

// Awake bodies in runs of this many per item of an integration stage. unit: bodies
constexpr std::uint32_t kBodiesPerItem = 64;

void SoftStepSolver::add_stage(Work work, std::uint32_t colour, std::uint32_t items) {
  if (items == 0) return;
  stages_.push_back({work, colour});
  stage_items_.push_back(items);
}

void SoftStepSolver::add_pass(Work work) {
  for (std::uint32_t colour = 0; colour < kColours; ++colour) {
    add_stage(work, colour, block_begin_[colour + 1] - block_begin_[colour]);
  }
  add_stage(work, kOverflowColour, overflow_.empty() ? 0u : 1u);
}

void SoftStepSolver::plan_stages(std::size_t awake, std::uint32_t substeps, bool warm_starting) {
  stages_.clear();
  stage_items_.clear();
  const auto runs = static_cast<std::uint32_t>((awake + kBodiesPerItem - 1) / kBodiesPerItem);
  for (std::uint32_t i = 0; i < substeps; ++i) {
    add_stage(Work::kIntegrateVelocities, 0, runs);
    if (warm_starting) add_pass(Work::kWarmStart);
    add_pass(Work::kSolve);
    add_stage(Work::kIntegratePositions, 0, runs);
    add_pass(Work::kRelax);
  }
  add_pass(Work::kRestitute);
}

void SoftStepSolver::run_item(const Stage& stage, std::uint32_t item, BodyStore& bodies,
                              const Vec3& gravity, float substep, const LaneSettings& settings) {
  if (stage.work == Work::kIntegrateVelocities || stage.work == Work::kIntegratePositions) {
    const std::span<const std::uint32_t> awake = bodies.awake();
    const std::size_t first = std::size_t{item} * kBodiesPerItem;
    const std::span<const std::uint32_t> run =
        awake.subspan(first, std::min<std::size_t>(kBodiesPerItem, awake.size() - first));
    if (stage.work == Work::kIntegrateVelocities) {
      integrate_velocities(run, gravity, substep);
    } else {
      integrate_positions(run, bodies, substep);
    }
    return;
  }
  const LaneBodies lanes = lane_bodies();
  if (stage.colour == kOverflowColour) {
    run_pass(single_lane_kernels(), stage.work, std::span(overflow_), lanes, settings);
    return;
  }
  run_pass(*kernels_, stage.work, std::span(blocks_.data() + block_begin_[stage.colour] + item, 1),
           lanes, settings);
}

template <int W>
void SoftStepSolver::run_pass(const LaneKernels<W>& kernels, Work work,
                              std::span<ManifoldBlock<W>> blocks, const LaneBodies& lanes,
                              const LaneSettings& settings) {
  switch (work) {
    case Work::kWarmStart:
      kernels.warm_start(blocks, lanes);
      return;
    case Work::kSolve:
    case Work::kRelax:
      kernels.solve(blocks, lanes, settings, work == Work::kSolve);
      return;
    case Work::kRestitute:
      bounces_.fetch_add(kernels.restitute(blocks, lanes, settings));
      return;
    case Work::kIntegrateVelocities:
    case Work::kIntegratePositions:
      return;  // run_item's, per run of bodies
  }
}

namespace {

// At most `most_spin` (unit: rad/s), the direction kept.
void bound_spin(Vec3& angular, float most_spin) {
  const float spin = angular.norm();
  if (spin > most_spin) angular *= most_spin / spin;
}

}  // namespace

void SoftStepSolver::integrate_velocities(std::span<const std::uint32_t> awake, const Vec3& gravity,
                                          float substep) {
  const Vec3 gained = gravity * substep;
  for (const std::uint32_t i : awake) velocity_[i].linear += gained;
}

// The bodies' poses by the solved velocities (rigid_body.h's integrator), and their motion since
// the step's start for the contacts' separations.
void SoftStepSolver::integrate_positions(std::span<const std::uint32_t> awake, BodyStore& bodies,
                                         float substep) {
  const std::span<Transform> poses = bodies.poses();
  const float most_spin = kMostTurnPerSubstep / substep;
  // The angular velocity changes too: the angular momentum is kept as the inertia turns.
  std::array<SpinningBody, kBodiesPerItem> spinning;
  for (std::size_t k = 0; k < awake.size(); ++k) {
    const std::uint32_t i = awake[k];
    bound_spin(velocity_[i].angular, most_spin);
    spinning[k] = {&poses[i], &velocity_[i].linear, &velocity_[i].angular,
                   &bodies.inertias_body()[i], &bodies.inverse_inertias_body()[i]};
  }
  integrate_positions_keeping_spin(std::span(spinning.data(), awake.size()), substep);
  for (const std::uint32_t i : awake) {
    motion_[i] = {poses[i].translation - position_[i],
                  (poses[i].rotation * rotation_[i].conjugate()).toRotationMatrix()};
  }
}

void SoftStepSolver::keep_impulses(std::span<ContactMemory> memory,
                                   const Parallel& parallel) const {
  // Contacts with no moving body were not solved: they start the next step afresh.
  parallel.for_each_run(memory.size(), kConstraintsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) memory[k] = ContactMemory{};
  });
  const auto keep = [&](const auto& block, int lane) {
    // An empty point has no mass along its normal.
    std::uint32_t count = 0;
    while (count < kManifoldPoints && block.points[count].mass[lane] > 0.0f) ++count;
    if (count == 0) return;
    const Vec3 normal(block.friction_normal[0][lane], block.friction_normal[1][lane],
                      block.friction_normal[2][lane]);
    const Vec3 tangent1(block.tangent1[0][lane], block.tangent1[1][lane], block.tangent1[2][lane]);
    const Vec3 friction = block.friction_impulse[0][lane] * tangent1 +
                          block.friction_impulse[1][lane] * normal.cross(tangent1);
    const float share = 1.0f / static_cast<float>(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      ContactMemory& kept = memory[block.contact[i][lane]];
      kept.normal_impulse = block.points[i].impulse[lane];
      kept.solved = true;
      kept.friction_impulse = share * friction;
      kept.twist_impulse = share * block.twist_impulse[lane];
    }
  };
  // Each contact is in one lane of one block: the blocks keep theirs on the threads.
  parallel.for_each(blocks_.size(), [&](std::size_t b) {
    for (int lane = 0; lane < kLaneWidth; ++lane) keep(blocks_[b], lane);
  });
  for (const ManifoldBlock<1>& block : overflow_) keep(block, 0);
}

ContactSolverStats SoftStepSolver::solve(BodyStore& bodies, std::span<const Contact> contacts,
                                         std::span<ContactMemory> memory,
                                         std::span<const PairMaterial> materials,
                                         const SolverSettings& settings, const Vec3& gravity,
                                         float dt, std::uint32_t substeps,
                                         const Parallel& parallel) {
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
  load_bodies(bodies, parallel);
  prepare(contacts, memory, settings, gravity, substep, parallel, stats);
  pack(materials, parallel);
  const LaneSettings lane_settings{.substep = substep,
                                   .inverse_substep = 1.0f / substep,
                                   .gravity = {gravity.x(), gravity.y(), gravity.z()},
                                   .linear_slop = settings.linear_slop,
                                   .max_correction_speed = settings.max_correction_speed,
                                   .rolling_resistance = settings.rolling_resistance,
                                   .restitution_threshold = settings.restitution_threshold};
  plan_stages(bodies.awake().size(), substeps, settings.warm_starting);
  bounces_.store(0);
  parallel.for_each_in_stages(stage_items_, [&](std::size_t stage, std::uint32_t item) {
    run_item(stages_[stage], item, bodies, gravity, substep, lane_settings);
  });
  stats.bounces = bounces_.load();
  // The relax and restitution passes come after the last substep bounded the turns: the
  // velocities the step leaves keep the same bound (else a light body squeezed between two 10⁹
  // times heavier ones gained spin from step to step until its square overflowed).
  const float most_spin = kMostTurnPerSubstep / substep;
  const std::span<const std::uint32_t> awake = bodies.awake();
  parallel.for_each_run(awake.size(), kConstraintsPerRun, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) bound_spin(velocity_[awake[k]].angular, most_spin);
  });
  store_solver_velocities(velocity_, parallel, bodies);
  keep_impulses(memory, parallel);
  kept_substep_ = substep;
  return stats;
}

}  // namespace sphys
