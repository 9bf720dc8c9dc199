// The soft step's constraints as manifolds in SIMD blocks: cut by body pair, coloured, packed with
// their friction at the centre of their points, and what the passes leave kept for the next step.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/buffers.h"
#include "core/place_in_runs.h"
#include "dynamics/contact_pairs.h"
#include "dynamics/group_by.h"
#include "dynamics/soft_step_solver.h"
#include "dynamics/tangent_basis.h"

namespace sphys {
namespace {

// The tangent rows are solved together while their effective mass's determinant is at least this
// share of its diagonal's product, one by one where it is less (nearly singular). unit:
// dimensionless
constexpr double kLeastTangentConditioning = 1e-6;

// A manifold's normals summed to less than this length cancel out (a body wedged between
// opposite faces): friction takes the first point's normal. unit: dimensionless
constexpr float kSmallestNormalSum = 1e-3f;

// A manifold whose friction impulse ends a step below this share of μ times its normal impulses
// stuck: friction held it. At the bound it slid. unit: dimensionless
constexpr float kStuckShareOfBound = 0.99f;

// Bodies that stuck hold to their anchor while they stay at rest relative to each other (their
// centres slip slower than SoftStepSolver::kAtRestSpeed), and while they turn against each other
// slower than this: a body rocking or rolling on its rounded underside moves its contact over its
// surface, and the anchor, a point of each body, held it rolling without a slip to lose its speed
// in (a bunny on the 1,000-bunny heap's floor rocked for two seconds and the heap had not slept
// by frame 880, in one of six seeds). unit: rad/s
constexpr float kMostStuckSpin = 0.1f;

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
                               const SoftStepContext& context, ManifoldBlock<W>& block,
                               int lane) const {
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
  const float bias_rate =
      against_immovable ? context.bias_rate_immovable : context.bias_rate_moving;
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
  // The anchor of the first point that kept one: a manifold's points share it.
  const Constraint* anchored = nullptr;
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
    if (anchored == nullptr && c.stuck) anchored = &c;
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

  // Static friction's anchor: the creep kept, in the new tangents, less the centres' offsets.
  // Static friction holds bodies that stuck and are still at rest relative to each other; a pair
  // struck or tumbling since slides, as Coulomb's friction has it, until it sticks again.
  if (pushed_out_[first.a] != 0 || pushed_out_[first.b] != 0) anchored = nullptr;
  if (anchored != nullptr) {
    const SolverVelocity& va = velocity_[first.a];
    const SolverVelocity& vb = velocity_[first.b];
    const Vec3 slip =
        vb.linear + vb.angular.cross(centre_b) - va.linear - va.angular.cross(centre_a);
    const Vec3 spin = vb.angular - va.angular;
    if (slip.squaredNorm() > kAtRestSpeed * kAtRestSpeed ||
        spin.squaredNorm() > kMostStuckSpin * kMostStuckSpin) {
      anchored = nullptr;
    }
  }
  const Vec3 creep = anchored != nullptr ? anchored->creep : Vec3::Zero();
  const Vec3 base_creep = creep - (centre_b - centre_a);
  block.stuck[lane] = anchored != nullptr ? 1.0f : 0.0f;
  block.base_creep[0][lane] = base_creep.dot(tangent1);
  block.base_creep[1][lane] = base_creep.dot(tangent2);
  const float spring = against_immovable ? context.spring_immovable : context.spring_moving;
  block.anchor_mass_scale[lane] = spring / (1.0f + spring);
  block.anchor_impulse_scale[lane] = 1.0f / (1.0f + spring);
}

// A body pair's contacts come one after another (the detector and the reducer emit them by pair):
// the pairs listed where their contacts begin, and cut into manifolds of at most kManifoldPoints
// each, in order, on the threads.
void SoftStepSolver::cut_manifolds(const Parallel& parallel) {
  const std::size_t count = constraints_.size();
  const std::size_t pairs = compact_in_runs(
      parallel, count, kConstraintsPerRun, [&](std::size_t j) { return pair_starts_[j] != 0; },
      [&](std::size_t kept) {
        resize_buffer(pair_first_, kept);
        resize_buffer(pairs_, kept);
      },
      [&](std::size_t position, std::size_t j) {
        pair_first_[position] = static_cast<std::uint32_t>(j);
        pairs_[position] = {constraints_[j].a, constraints_[j].b};
      },
      run_first_);
  const auto points_of = [&](std::size_t p) {
    return (p + 1 < pairs ? pair_first_[p + 1] : static_cast<std::uint32_t>(count)) -
           pair_first_[p];
  };
  place_in_runs(
      parallel, pairs, kConstraintsPerRun, count,
      [&](std::size_t p) { return (points_of(p) + kManifoldPoints - 1) / kManifoldPoints; },
      [&](std::size_t manifolds) {
        resize_buffer(manifolds_, manifolds);
        resize_buffer(manifold_bodies_, manifolds);
      },
      [&](std::size_t first, std::size_t p) {
        const Constraint& c = constraints_[pair_first_[p]];
        for (std::uint32_t done = 0; done < points_of(p); done += kManifoldPoints, ++first) {
          manifolds_[first] = {pair_first_[p] + done,
                               std::min<std::uint32_t>(kManifoldPoints, points_of(p) - done)};
          manifold_bodies_[first] = {c.a, c.b, c.a_moves, c.b_moves};
        }
      },
      run_first_);
}

void SoftStepSolver::colour_manifolds() {
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

void SoftStepSolver::pack(std::span<const PairMaterial> materials, const SoftStepContext& context) {
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
  context.parallel.for_each(blocks, [&](std::size_t b) {
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
      pack_lane(manifold, materials[constraints_[manifolds_[manifold].first].contact], context,
                block, static_cast<int>(k - first));
    }
  });
  const std::uint32_t overflow_begin = colour_first(kOverflowColour);
  resize_buffer(overflow_, colour_first(kOverflowColour + 1) - overflow_begin);
  for (std::size_t k = 0; k < overflow_.size(); ++k) {
    empty(overflow_[k]);
    const std::uint32_t manifold = by_colour_[overflow_begin + k];
    pack_lane(manifold, materials[constraints_[manifolds_[manifold].first].contact], context,
              overflow_[k], 0);
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
    const Vec3 tangent2 = normal.cross(tangent1);
    const float t1 = block.friction_impulse[0][lane];
    const float t2 = block.friction_impulse[1][lane];
    const Vec3 friction = t1 * tangent1 + t2 * tangent2;
    // The bodies stick while friction stays inside its bound; at the bound they slide, and the
    // anchor goes (Coulomb's sliding friction, nothing pulling back).
    float pushed = 0.0f;
    for (std::uint32_t i = 0; i < count; ++i) pushed += block.points[i].impulse[lane];
    const float bound = kStuckShareOfBound * block.friction[lane] * pushed;
    const bool stuck = t1 * t1 + t2 * t2 < bound * bound;
    // The creep since the anchor was set; a manifold that only now sticks anchors where it is.
    Vec3 creep = Vec3::Zero();
    if (stuck && block.stuck[lane] > 0.0f) {
      const auto lane_vector = [&](const auto& v) {
        return Vec3(v[0][lane], v[1][lane], v[2][lane]);
      };
      const SolverMotion& a = motion_[block.body_a[lane]];
      const SolverMotion& b = motion_[block.body_b[lane]];
      const Vec3 offsets = b.moved - a.moved + b.turned * lane_vector(block.centre_b) -
                           a.turned * lane_vector(block.centre_a);
      creep = (block.base_creep[0][lane] + tangent1.dot(offsets)) * tangent1 +
              (block.base_creep[1][lane] + tangent2.dot(offsets)) * tangent2;
    }
    const float share = 1.0f / static_cast<float>(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      ContactMemory& kept = memory[block.contact[i][lane]];
      kept.normal_impulse = block.points[i].impulse[lane];
      kept.solved = true;
      kept.friction_impulse = share * friction;
      kept.twist_impulse = share * block.twist_impulse[lane];
      kept.creep = creep;
      kept.stuck = stuck;
    }
  };
  // Each contact is in one lane of one block: the blocks keep theirs on the threads.
  parallel.for_each(blocks_.size(), [&](std::size_t b) {
    for (int lane = 0; lane < kLaneWidth; ++lane) keep(blocks_[b], lane);
  });
  for (const ManifoldBlock<1>& block : overflow_) keep(block, 0);
}

}  // namespace sphys
