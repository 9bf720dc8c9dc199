#pragma once

// The soft step's passes over blocks of manifolds, written once over a lane type F
// (core/simd.h): every lane does the same arithmetic whatever F is, so the intrinsics and the
// plain floats give the same bits. Included by contact_lanes.cpp (and the tests), never by a file
// that includes Eigen, as contact_lanes.cpp may be compiled for AVX2.

#include <cstdint>
#include <span>

#include "dynamics/contact_lanes.h"
#include "dynamics/lane_pair.h"

namespace sphys::lanes {

template <class F>
void warm_start(std::span<ManifoldBlock<F::kWidth>> blocks, const LaneBodies& bodies) {
  constexpr int W = F::kWidth;
  for (ManifoldBlock<W>& m : blocks) {
    LanePair<F> pair(m, bodies);
    // The points' normal impulses summed: linear, and their moments about each centre.
    V3<F> linear{F::splat(0.0f), F::splat(0.0f), F::splat(0.0f)};
    V3<F> moment_a = linear;
    V3<F> moment_b = linear;
    for (std::uint32_t i = 0; i < m.point_count; ++i) {
      const auto& p = m.points[i];
      const V3<F> impulse = F::load(p.impulse) * load3<F>(p.normal);
      linear = linear + impulse;
      moment_a = moment_a + cross(load3<F>(p.ra), impulse);
      moment_b = moment_b + cross(load3<F>(p.rb), impulse);
    }
    // Friction at the centre, and the twist about the normal.
    const FrictionFrame<F> frame(m);
    const V3<F> friction = F::load(m.friction_impulse[0]) * frame.tangent1 +
                           F::load(m.friction_impulse[1]) * frame.tangent2;
    linear = linear + friction;
    moment_a = moment_a + cross(load3<F>(m.centre_a), friction);
    moment_b = moment_b + cross(load3<F>(m.centre_b), friction);
    const V3<F> turn = F::load(m.twist_impulse) * frame.normal + load3<F>(m.rolling_impulse);
    pair.a.linear = pair.a.linear - pair.inverse_mass_a * linear;
    pair.b.linear = pair.b.linear + pair.inverse_mass_b * linear;
    pair.a.angular = pair.a.angular - times<F>(pair.inverse_inertia_a, moment_a + turn);
    pair.b.angular = pair.b.angular + times<F>(pair.inverse_inertia_b, moment_b + turn);
    pair.scatter(m, bodies);
  }
}

// A vector's length clamped to `limit` (>= 0): the factor that scales it there, 1 inside.
template <class F>
F clamp_scale(const F& length_squared, const F& limit) {
  const auto outside = length_squared > limit * limit;
  return select(outside, limit / sqrt(length_squared), F::splat(1.0f));
}

// Static friction's pull back to the anchor, in the lanes where it is active: a bias speed along
// each tangent (unit: m/s) and the anchor spring's share of the rigid impulse and of the
// accumulated one.
template <class F>
struct Anchor {
  F bias1, bias2;
  F mass_scale, impulse_scale;
  typename F::Mask active;
};

// Friction at the manifold's centre, Coulomb's: the two tangent rows solved together (the 2 × 2
// effective mass's inverse), the tangential impulse kept inside the disc of radius `bound` (μ Σ
// λn). With an anchor, the lanes where it is active also pull the centre back; the others keep
// their impulse.
template <class F>
void solve_friction(ManifoldBlock<F::kWidth>& m, LanePair<F>& pair, const V3<F>& tangent1,
                    const V3<F>& tangent2, const F& bound, const Anchor<F>* anchor = nullptr) {
  const V3<F> ca = load3<F>(m.centre_a);
  const V3<F> cb = load3<F>(m.centre_b);
  const V3<F> slip = pair.relative_velocity(ca, cb);
  F slip1 = dot(tangent1, slip);
  F slip2 = dot(tangent2, slip);
  F mass_scale = F::splat(1.0f);
  F impulse_scale = F::splat(0.0f);
  if (anchor != nullptr) {
    slip1 = slip1 + anchor->bias1;
    slip2 = slip2 + anchor->bias2;
    mass_scale = anchor->mass_scale;
    impulse_scale = anchor->impulse_scale;
  }
  const F old1 = F::load(m.friction_impulse[0]);
  const F old2 = F::load(m.friction_impulse[1]);
  const F k11 = F::load(m.tangent_mass[0]);
  const F k12 = F::load(m.tangent_mass[1]);
  const F k22 = F::load(m.tangent_mass[2]);
  F t1 = old1 - mass_scale * (k11 * slip1 + k12 * slip2) - impulse_scale * old1;
  F t2 = old2 - mass_scale * (k12 * slip1 + k22 * slip2) - impulse_scale * old2;
  const F scale = clamp_scale(t1 * t1 + t2 * t2, bound);
  t1 = scale * t1;
  t2 = scale * t2;
  if (anchor != nullptr) {
    t1 = select(anchor->active, t1, old1);
    t2 = select(anchor->active, t2, old2);
  }
  t1.store(m.friction_impulse[0]);
  t2.store(m.friction_impulse[1]);
  pair.push(ca, cb, (t1 - old1) * tangent1 + (t2 - old2) * tangent2);
}

// One pass. With the bias (the solve) a penetrating contact is pushed apart by its spring-damper;
// without it (the relax) contacts only stop approaching and sliding, so that the push leaves no
// speed behind. A gap may close within the substep and no more, either way.
template <class F>
void solve(std::span<ManifoldBlock<F::kWidth>> blocks, const LaneBodies& bodies,
           const LaneSettings& settings, bool use_bias) {
  constexpr int W = F::kWidth;
  const F zero = F::splat(0.0f);
  const F one = F::splat(1.0f);
  const F inverse_substep_dt = F::splat(settings.inverse_substep_dt);
  const F slop = F::splat(settings.linear_slop);
  const F most_correction = F::splat(-settings.max_correction_speed);
  for (ManifoldBlock<W>& m : blocks) {
    LanePair<F> pair(m, bodies);
    const LaneMotion<F> motion_a = LaneMotion<F>::gather(bodies, m.body_a);
    const LaneMotion<F> motion_b = LaneMotion<F>::gather(bodies, m.body_b);
    const F bias_rate = F::load(m.bias_rate);
    const F friction = F::load(m.friction);
    const FrictionFrame<F> frame(m);
    // Static friction: in the solve pass, where the bodies stuck at the last step's end, the
    // centre is pulled back to where they stuck by the anchor's spring. Before the points' push,
    // which then has the last word: solved after it, static friction held a resting pile's
    // overlaps where they were, along whatever part of each point's normal is tangent to the
    // manifold's, and a heap of 10,000 bunnies slept 1.2 mm deep, against 0.85 mm without it.
    // Elsewhere friction stays out of the solve pass: beside the push out of penetration it took
    // part of that impulse along the surface, and a bunny shot at 100 m/s into another went 5.9%
    // of a bunny deep.
    if (use_bias) {
      const auto stuck = F::load(m.stuck) > zero;
      if (any(stuck)) {
        F kept = zero;
        for (std::uint32_t i = 0; i < m.point_count; ++i)
          kept = kept + F::load(m.points[i].impulse);
        const V3<F> ca = load3<F>(m.centre_a);
        const V3<F> cb = load3<F>(m.centre_b);
        // The creep now: the kept creep less the centres' offsets at the step's start, plus
        // their offsets now.
        const V3<F> offsets = motion_b.moved - motion_a.moved + times<F>(motion_b.turned, cb) -
                              times<F>(motion_a.turned, ca);
        const F creep1 = F::load(m.base_creep[0]) + dot(frame.tangent1, offsets);
        const F creep2 = F::load(m.base_creep[1]) + dot(frame.tangent2, offsets);
        const F most = F::splat(settings.max_anchor_speed);
        const F least = zero - most;
        const Anchor<F> anchor{.bias1 = max(min(bias_rate * creep1, most), least),
                               .bias2 = max(min(bias_rate * creep2, most), least),
                               .mass_scale = F::load(m.anchor_mass_scale),
                               .impulse_scale = F::load(m.anchor_impulse_scale),
                               .active = stuck};
        solve_friction(m, pair, frame.tangent1, frame.tangent2, friction * kept, &anchor);
      }
    }
    F pushed = zero;       // the points' normal impulses summed: friction's bound
    F twist_bound = zero;  // each times its lever: the twist's bound
    for (std::uint32_t i = 0; i < m.point_count; ++i) {
      auto& p = m.points[i];
      const V3<F> normal = load3<F>(p.normal);
      const V3<F> ra = load3<F>(p.ra);
      const V3<F> rb = load3<F>(p.rb);
      // The separation now, from the bodies' motion since the step's start (anchors carried).
      const V3<F> moved = motion_b.moved - motion_a.moved + times<F>(motion_b.turned, rb) -
                          times<F>(motion_a.turned, ra);
      const F separation = F::load(p.base_separation) + dot(normal, moved);
      const auto apart = separation > zero;
      F bias = select(apart, separation * inverse_substep_dt, zero);
      F mass_scale = one;
      F impulse_scale = zero;
      if (use_bias) {
        const F soft_mass = F::load(p.mass_scale);
        // Within the slop the contact is rigid, its spring only pushes what lies deeper: the
        // spring's give under a resting load added up to a millimetre under a deep heap.
        const F error = min(separation + slop, zero);
        const auto springy = error < zero;
        bias = select(apart, bias, max(soft_mass * bias_rate * error, most_correction));
        mass_scale = select(springy, soft_mass, one);
        impulse_scale = select(springy, F::load(p.impulse_scale), zero);
      }
      const F speed = dot(normal, pair.relative_velocity(ra, rb));
      // The fastest approach met in the solve passes: a body falling onto a contact within the
      // step meets it at the speed gravity gave it by then, not the step's start speed.
      if (use_bias) min(F::load(p.approach), speed).store(p.approach);
      const F old_normal = F::load(p.impulse);
      const F normal_impulse = max(
          old_normal - F::load(p.mass) * (mass_scale * speed + bias) - impulse_scale * old_normal,
          zero);
      normal_impulse.store(p.impulse);
      max(F::load(p.max_normal_impulse), normal_impulse).store(p.max_normal_impulse);
      pair.push(ra, rb, (normal_impulse - old_normal) * normal);
      pushed = pushed + normal_impulse;
      twist_bound = twist_bound + F::load(p.lever) * normal_impulse;
    }
    {
      // Twist: the bodies' relative spin about the normal, within μ Σ lever λn; in both passes,
      // as the push out of penetration does not turn bodies about the normal (in the relax pass
      // only, the 48 bunnies of Determinism.PlausibleMode... slept 81 frames later).
      const F old_twist = F::load(m.twist_impulse);
      const F spin = dot(frame.normal, pair.b.angular - pair.a.angular);
      const F twist_limit = friction * twist_bound;
      const F twist =
          max(min(old_twist - F::load(m.twist_mass) * spin, twist_limit), zero - twist_limit);
      twist.store(m.twist_impulse);
      pair.turn((twist - old_twist) * frame.normal);
    }
    // The relax pass's friction comes after the points' push, within its bound.
    if (!use_bias) solve_friction(m, pair, frame.tangent1, frame.tangent2, friction * pushed);
    // In the relax pass only (as Box2D v3): resisting the turns that the solve pass's push out of
    // penetration gives kept piles rocking.
    if (settings.rolling_resistance > 0.0f && !use_bias) {
      // Rolling resistance: an angular impulse against the pair's relative turning (rolling and
      // spinning), at most the arm times the manifold's normal impulse.
      const V3<F> old = load3<F>(m.rolling_impulse);
      V3<F> rolling = old - times<F>(m.rolling_mass, pair.b.angular - pair.a.angular);
      const F limit = F::splat(settings.rolling_resistance) * pushed;
      rolling = clamp_scale(dot(rolling, rolling), limit) * rolling;
      store3(rolling, m.rolling_impulse);
      pair.turn(rolling - old);
    }
    pair.scatter(m, bodies);
  }
}

// Restitution once the substeps are done (as Box2D does it): a point that approached faster than
// the threshold and pushed during the step leaves at ε times that speed, plus (1 + ε) times half
// a substep of the gravity closing it. Semi-implicit Euler keeps ½ v² + g y − ½ g v_y h in flight,
// not the energy: a ball meets the ground with ½ g h of speed more than its fall gives, and
// leaves with ½ g h less than it climbs on. With the half substep the rebound climbs to ε² times
// the fall (its apex at rest, where the kept figure is the energy), and ε = 1 keeps the kept
// figure, not raising it.
// Sweeps of a manifold's restitution rows: enough for four points to settle on their targets.
inline constexpr int kRestitutionSweeps = 4;

template <class F>
std::uint32_t restitute(std::span<ManifoldBlock<F::kWidth>> blocks, const LaneBodies& bodies,
                        const LaneSettings& settings) {
  constexpr int W = F::kWidth;
  const F zero = F::splat(0.0f);
  const F one = F::splat(1.0f);
  const F threshold = F::splat(-settings.restitution_threshold);
  const F half_substep_dt = F::splat(0.5f * settings.substep_dt);
  const V3<F> gravity{F::splat(settings.gravity[0]), F::splat(settings.gravity[1]),
                      F::splat(settings.gravity[2])};
  F bounces = zero;
  for (ManifoldBlock<W>& m : blocks) {
    const F restitution = F::load(m.restitution);
    // Gravity acts on the bodies that move: the one their relative acceleration comes from.
    const auto a_falls = F::load(m.inverse_mass_a) > zero;
    const auto b_falls = F::load(m.inverse_mass_b) > zero;
    const V3<F> gravity_a{select(a_falls, gravity.x, zero), select(a_falls, gravity.y, zero),
                          select(a_falls, gravity.z, zero)};
    const V3<F> gravity_b{select(b_falls, gravity.x, zero), select(b_falls, gravity.y, zero),
                          select(b_falls, gravity.z, zero)};
    // Which points bounce, and the speed each leaves at; a block none of whose points bounces
    // (a resting pile's) is left as it is.
    typename F::Mask bounce[kManifoldPoints];
    F target[kManifoldPoints];
    bool any_bounce = false;
    for (std::uint32_t i = 0; i < m.point_count; ++i) {
      const auto& p = m.points[i];
      const F approach = F::load(p.approach);
      bounce[i] =
          (restitution > zero) & (F::load(p.max_normal_impulse) > zero) & (approach < threshold);
      any_bounce = any_bounce || any(bounce[i]);
      bounces = bounces + select(bounce[i], one, zero);
      const F closing_gravity =
          dot(load3<F>(p.normal), gravity_b - gravity_a);  // negative when closing
      target[i] =
          zero - restitution * approach - (one + restitution) * half_substep_dt * closing_gravity;
    }
    if (!any_bounce) continue;
    // The bouncing points together: one point's push turns the body and changes what the others
    // need, and in one sequential sweep the points of a rounded sphere-tree landing on three or
    // four at once sent it 12% to 35% higher than ε² times its fall. Sweeps over the manifold
    // until each point leaves at its target, each point's impulse kept at or above zero (the
    // projected Gauss-Seidel of the manifold's restitution rows).
    LanePair<F> pair(m, bodies);
    for (int sweep = 0; sweep < kRestitutionSweeps; ++sweep) {
      for (std::uint32_t i = 0; i < m.point_count; ++i) {
        auto& p = m.points[i];
        const V3<F> normal = load3<F>(p.normal);
        const V3<F> ra = load3<F>(p.ra);
        const V3<F> rb = load3<F>(p.rb);
        const F old = F::load(p.impulse);
        const F speed = dot(normal, pair.relative_velocity(ra, rb));
        const F total = max(old - F::load(p.mass) * (speed - target[i]), zero);
        const F impulse = select(bounce[i], total, old);
        impulse.store(p.impulse);
        pair.push(ra, rb, (impulse - old) * normal);
      }
    }
    pair.scatter(m, bodies);
  }
  alignas(32) float counted[W];
  bounces.store(counted);
  std::uint32_t total = 0;
  for (const float c : counted) total += static_cast<std::uint32_t>(c);
  return total;
}

}  // namespace sphys::lanes
