#pragma once

// Bodies and joints for the joints' tests: balls, rods as links, a chain hanging from the world.

#include <cstdint>
#include <vector>

#include "sphys/world.h"
#include "support/world_scenes.h"

namespace sphys::test {

// A rod along x of `length` and `radius` (unit: m) and `mass` (unit: kg), centred at
// `position`, whose tree is one sphere of its radius at its centre: a solid cylinder's inertia.
inline BodyDesc rod_body(float length, float radius, float mass, const Vec3& position) {
  BodyDesc desc = ball_body(radius, mass, position);
  const float across = mass * (3.0f * radius * radius + length * length) / 12.0f;
  desc.inertia = Vec3(0.5f * mass * radius * radius, across, across).asDiagonal();
  return desc;
}

// A hinge about z (or another joint type) between two bodies (or the world: a null id) at a
// world point, the anchors placed from the bodies' poses.
inline JointDesc joint_at(const World& world, JointType type, BodyId a, BodyId b, const Vec3& point,
                          const Vec3& axis = Vec3::UnitZ()) {
  JointDesc desc;
  desc.type = type;
  desc.body_a = a;
  desc.body_b = b;
  const auto local = [&](BodyId body) {
    if (body.is_null()) return point;
    const Transform pose = world.body(body).pose;
    return Vec3(pose.rotation.conjugate() * (point - pose.translation));
  };
  const auto local_axis = [&](BodyId body) {
    return body.is_null() ? axis : Vec3(world.body(body).pose.rotation.conjugate() * axis);
  };
  desc.anchor_a = local(a);
  desc.anchor_b = local(b);
  desc.axis_a = local_axis(a);
  desc.axis_b = local_axis(b);
  return desc;
}

// A chain of `links` rods of `link_length` (unit: m) and 1 kg, hinged about z to each other and
// its first to the world at `top`, laid along `direction` (a unit vector); with `end_mass` > 0 a
// ball of that mass (unit: kg) hangs from its last link. The joints in order from the top.
struct Chain {
  std::vector<BodyId> links;
  std::vector<JointId> joints;
};
inline Chain hang_chain(World& world, int links, float link_length, const Vec3& top,
                        const Vec3& direction, float end_mass = 0.0f) {
  Chain chain;
  const float radius = 0.2f * link_length;
  BodyId above;  // the world
  for (int i = 0; i < links; ++i) {
    const Vec3 start = top + static_cast<float>(i) * link_length * direction;
    BodyDesc desc = rod_body(link_length, radius, 1.0f, start + 0.5f * link_length * direction);
    desc.pose.rotation = Quat::FromTwoVectors(Vec3::UnitX(), direction);
    const BodyId link = world.add_body(desc);
    chain.joints.push_back(world.add_joint(joint_at(world, JointType::kHinge, above, link, start)));
    chain.links.push_back(link);
    above = link;
  }
  if (end_mass > 0.0f) {
    const Vec3 end = top + static_cast<float>(links) * link_length * direction;
    const float ball_radius = 2.0f * radius;
    const BodyId ball =
        world.add_body(ball_body(ball_radius, end_mass, end + ball_radius * direction));
    chain.joints.push_back(world.add_joint(joint_at(world, JointType::kHinge, above, ball, end)));
    chain.links.push_back(ball);
  }
  return chain;
}

// The largest gap of the joints now. unit: m
inline float largest_gap(const World& world, const std::vector<JointId>& joints) {
  float largest = 0.0f;
  for (const JointId joint : joints) largest = std::max(largest, world.joint_state(joint).gap);
  return largest;
}

}  // namespace sphys::test
