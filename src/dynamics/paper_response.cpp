#include "dynamics/paper_response.h"

namespace sphys {
namespace {

// One pass over the contacts in order; returns the impulses applied. The ground plane is static:
// no velocity, no inverse mass, restitution `ground_restitution`.
std::uint32_t paper_pass(BodyStore& bodies, std::span<const Contact> contacts,
                         float ground_restitution) {
  const std::span<const Transform> poses = bodies.poses();
  const std::span<Vec3> linear = bodies.linear_velocities();
  const std::span<Vec3> angular = bodies.angular_velocities();
  const std::span<const float> inverse_mass = bodies.inverse_masses();
  const std::span<const Mat3> inverse_inertia = bodies.inverse_inertias_world();
  // 1/m + n·((I⁻¹(r × n)) × r) of a moving body.
  const auto inverse_effective_mass = [&](std::uint32_t body, const Vec3& r, const Vec3& n) {
    return inverse_mass[body] + n.dot((inverse_inertia[body] * r.cross(n)).cross(r));
  };
  std::uint32_t impulses = 0;
  for (const Contact& contact : contacts) {
    const std::uint32_t a = contact.body_a;
    const std::uint32_t b = contact.body_b;
    const bool a_moves = a != kGroundPlaneBody && bodies.dynamic()[a] != 0;
    const bool b_moves = bodies.dynamic()[b] != 0;
    const Vec3& n = contact.normal;
    const Vec3 ra =
        a != kGroundPlaneBody ? Vec3(contact.point - poses[a].translation) : contact.point;
    const Vec3 rb = contact.point - poses[b].translation;
    const Vec3 velocity_a = a_moves ? Vec3(linear[a] + angular[a].cross(ra)) : Vec3::Zero();
    const Vec3 velocity_b = b_moves ? Vec3(linear[b] + angular[b].cross(rb)) : Vec3::Zero();
    const float approach = n.dot(velocity_b - velocity_a);
    if (!(approach < 0.0f)) continue;

    const float denominator = (a_moves ? inverse_effective_mass(a, ra, n) : 0.0f) +
                              (b_moves ? inverse_effective_mass(b, rb, n) : 0.0f);
    if (!(denominator > 0.0f)) continue;  // two static bodies: nothing can move
    const float epsilon =
        mix_restitution(a != kGroundPlaneBody ? bodies.restitutions()[a] : ground_restitution,
                        bodies.restitutions()[b]);
    const Vec3 impulse = (-(1.0f + epsilon) * approach / denominator) * n;

    if (a_moves) {
      linear[a] -= inverse_mass[a] * impulse;
      angular[a] -= inverse_inertia[a] * ra.cross(impulse);
    }
    if (b_moves) {
      linear[b] += inverse_mass[b] * impulse;
      angular[b] += inverse_inertia[b] * rb.cross(impulse);
    }
    ++impulses;
  }
  return impulses;
}

}  // namespace

PaperResponseStats apply_paper_response(BodyStore& bodies, std::span<const Contact> contacts,
                                        float ground_restitution, std::uint32_t max_passes) {
  PaperResponseStats stats;
  while (stats.passes < max_passes) {
    const std::uint32_t impulses = paper_pass(bodies, contacts, ground_restitution);
    ++stats.passes;
    stats.impulses += impulses;
    if (impulses == 0) break;
  }
  return stats;
}

}  // namespace sphys
