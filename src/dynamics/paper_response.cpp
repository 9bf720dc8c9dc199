#include "dynamics/paper_response.h"

namespace sphys {
namespace {

// The ground plane as a body: static, so it takes no impulse and has infinite mass.
RigidBody ground_body(float restitution) {
  RigidBody ground;
  ground.is_static = true;
  ground.restitution = restitution;
  return ground;
}

// 1/m + n·((I⁻¹(r × n)) × r) of one body; zero for a static body.
float inverse_effective_mass(const RigidBody& body, const Mat3& inverse_inertia, const Vec3& r,
                             const Vec3& n) {
  if (body.is_static) return 0.0f;
  return body.inverse_mass + n.dot((inverse_inertia * r.cross(n)).cross(r));
}

// One pass over the contacts in order; returns the impulses applied.
std::uint32_t paper_pass(std::span<RigidBody> bodies, std::span<const Contact> contacts,
                         RigidBody& ground) {
  std::uint32_t impulses = 0;
  for (const Contact& contact : contacts) {
    RigidBody& a = contact.body_a == kGroundPlaneBody ? ground : bodies[contact.body_a];
    RigidBody& b = bodies[contact.body_b];
    const Vec3& n = contact.normal;
    const float approach = n.dot(b.velocity_at(contact.point) - a.velocity_at(contact.point));
    if (!(approach < 0.0f)) continue;

    const Vec3 ra = contact.point - a.pose.translation;
    const Vec3 rb = contact.point - b.pose.translation;
    const Mat3 inverse_inertia_a = a.is_static ? Mat3::Zero() : a.inverse_inertia_world();
    const Mat3 inverse_inertia_b = b.is_static ? Mat3::Zero() : b.inverse_inertia_world();
    const float denominator = inverse_effective_mass(a, inverse_inertia_a, ra, n) +
                              inverse_effective_mass(b, inverse_inertia_b, rb, n);
    if (!(denominator > 0.0f)) continue;  // two static bodies: nothing can move
    const float epsilon = mix_restitution(a.restitution, b.restitution);
    const Vec3 impulse = (-(1.0f + epsilon) * approach / denominator) * n;

    if (!a.is_static) {
      a.linear_velocity -= a.inverse_mass * impulse;
      a.angular_velocity -= inverse_inertia_a * ra.cross(impulse);
    }
    if (!b.is_static) {
      b.linear_velocity += b.inverse_mass * impulse;
      b.angular_velocity += inverse_inertia_b * rb.cross(impulse);
    }
    ++impulses;
  }
  return impulses;
}

}  // namespace

PaperResponseStats apply_paper_response(std::span<RigidBody> bodies,
                                        std::span<const Contact> contacts, float ground_restitution,
                                        std::uint32_t max_passes) {
  RigidBody ground = ground_body(ground_restitution);
  PaperResponseStats stats;
  while (stats.passes < max_passes) {
    const std::uint32_t impulses = paper_pass(bodies, contacts, ground);
    ++stats.passes;
    stats.impulses += impulses;
    if (impulses == 0) break;
  }
  return stats;
}

}  // namespace sphys
