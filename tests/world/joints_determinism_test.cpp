// A jointed scene computes the same bits on 1, 2 and 4 threads and in every set of lanes: the
// joints' passes run on one thread in one order, between the contacts' colours.

#include <bit>
#include <cstdint>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "support/joint_scenes.h"

namespace sphys {
namespace {

// FNV-1a over every body's pose and velocities, bit for bit.
std::uint64_t state_hash(const World& world) {
  std::uint64_t hash = 0xcbf29ce484222325u;
  const auto add = [&](float value) {
    const auto bits = std::bit_cast<std::uint32_t>(value);
    for (int byte = 0; byte < 4; ++byte)
      hash = (hash ^ ((bits >> (8 * byte)) & 0xffu)) * 0x100000001b3u;
  };
  for (std::uint32_t slot = 0; slot < world.body_slots(); ++slot) {
    const RigidBody body = world.body(world.id_of(slot));
    for (int k = 0; k < 3; ++k) {
      add(body.pose.translation[k]);
      add(body.linear_velocity[k]);
      add(body.angular_velocity[k]);
    }
    for (int k = 0; k < 4; ++k) add(body.pose.rotation.coeffs()[k]);
  }
  return hash;
}

// Two chains of 10 links, one with a heavy ball, swinging into a heap of 40 balls on the floor,
// with ball joints, a slider and a weld among them; 240 frames.
std::uint64_t run(std::uint32_t threads, SolverLanes lanes) {
  WorldSettings settings = test::on_plane(0.5f, 0.2f);
  settings.threads = threads;
  settings.solver.lanes = lanes;
  World world(settings);
  for (int i = 0; i < 40; ++i) {
    world.add_body(test::ball_body(
        0.15f, 1.0f,
        Vec3(0.3f * static_cast<float>(i % 5) - 0.6f, 0.15f + 0.3f * static_cast<float>(i / 10),
             0.3f * static_cast<float>((i / 5) % 2))));
  }
  const test::Chain chain =
      test::hang_chain(world, 10, 0.2f, Vec3(-2.0f, 2.5f, 0.1f), Vec3::UnitX());
  test::hang_chain(world, 10, 0.2f, Vec3(2.0f, 2.5f, 0.2f), -Vec3::UnitX(), 20.0f);
  const BodyId slid = world.add_body(test::ball_body(0.1f, 1.0f, Vec3(0.0f, 3.0f, 0.0f)));
  world.add_joint(test::joint_at(world, JointType::kSlider, chain.links.back(), slid,
                                 world.body(slid).pose.translation, Vec3::UnitY()));
  const BodyId welded = world.add_body(test::ball_body(0.1f, 1.0f, Vec3(0.0f, 3.5f, 0.5f)));
  world.add_joint(test::joint_at(world, JointType::kWeld, slid, welded, Vec3(0.0f, 3.2f, 0.2f)));
  for (int frame = 0; frame < 240; ++frame) world.step(1.0f / 60.0f);
  return state_hash(world);
}

TEST(JointsDeterminism, AJointedSceneIsTheSameOnAnyThreadsAndLanes) {
  const std::uint64_t reference = run(1, SolverLanes::kPortable);
  for (const SolverLanes lanes : {SolverLanes::kPortable, SolverLanes::kSse2, SolverLanes::kAvx2}) {
    try {
      (void)resolve_solver_lanes(lanes);
    } catch (const Error&) {
      continue;  // AVX2 on a processor without it
    }
    for (const std::uint32_t threads : {1u, 2u, 4u}) {
      EXPECT_EQ(run(threads, lanes), reference) << solver_lanes_name(lanes) << ", " << threads;
    }
  }
}

}  // namespace
}  // namespace sphys
