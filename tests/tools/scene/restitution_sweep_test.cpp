// Restitution does not depend on a body's size, mass, drop height or sphere-tree: a ball of radius
// 5 cm to 1 m, light or heavy, dropped from 0.5 or 2 m with ε = 0.5 or 0.9 onto a plane of
// restitution 0 (a pair takes the larger), climbs back to ε² times its fall, whether its tree is
// one sphere or three levels of an octree over its icosphere mesh (which meets the plane on
// several spheres at once).

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "sphys/tools/build_world.h"
#include "sphys/tools/primitives.h"
#include "support/obj_text.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

constexpr float kFrame = 1.0f / 60.0f;  // unit: s

struct Bounce {
  float fall = 0.0f;   // from the drop to where the tree first touches the plane. unit: m
  float climb = 0.0f;  // from there to the apex after the first impact. unit: m
};

// Drops the ball from `height` (its lowest leaf sphere above the plane) and measures its centre.
Bounce drop(const std::filesystem::path& mesh, const std::filesystem::path& cache, double radius,
            int depth, double density, float restitution, float height) {
  Scene scene;
  scene.name = "restitution sweep";
  scene.ground.kind = GroundSpec::Kind::kPlane;
  scene.ground.restitution = 0.0f;
  BodySpec ball;
  ball.mesh = mesh.string();
  ball.size = 2.0 * radius;
  ball.tree.method = BuildMethod::Octree;
  ball.tree.depth = depth;
  ball.density = density;
  ball.restitution = restitution;
  scene.bodies = {ball};
  BuildWorldOptions options;
  options.cache_dir = cache;
  // Built once at the origin to find how far the tree reaches below the centre (unturned), then
  // placed so that its lowest leaf is `height` above the plane.
  float reach = 0.0f;
  {
    const SimulationSetup probe = build_world(scene, options);
    const SphereTree& tree = probe.world->tree(probe.bodies[0]);
    for (const std::uint32_t leaf : tree.leaves()) {
      reach = std::max(reach, tree.sphere(leaf).radius - tree.sphere(leaf).center.y());
    }
  }
  scene.bodies[0].position = Vec3(0.0f, reach + height, 0.0f);
  const SimulationSetup setup = build_world(scene, options);
  World& world = *setup.world;
  float apex = -std::numeric_limits<float>::infinity();
  bool risen = false;
  for (int frame = 0; frame < 300; ++frame) {
    EXPECT_FALSE(world.step(kFrame).non_finite_body);
    const RigidBody body = world.body(setup.bodies[0]);
    const float bottom = body.pose.translation.y() - reach;
    if (body.linear_velocity.y() > 0.0f) risen = true;
    if (!risen) continue;
    apex = std::max(apex, bottom);
    if (body.linear_velocity.y() <= 0.0f) break;  // past the apex
  }
  return {height, apex};
}

TEST(RestitutionSweep, ABallClimbsToEpsilonSquaredItsFallWhateverItsSizeMassHeightAndTree) {
  const test::TempDir dir;
  const std::filesystem::path mesh = dir.write("ball.obj", test::obj_text(make_icosphere(1.0, 3)));
  const std::filesystem::path cache = dir.path() / "trees";
  for (const int depth : {1, 3}) {
    for (const double radius : {0.05, 0.25, 0.5, 1.0}) {
      for (const double density : {100.0, 8000.0}) {
        for (const float height : {0.5f, 2.0f}) {
          for (const float restitution : {0.5f, 0.9f}) {
            SCOPED_TRACE(testing::Message()
                         << "tree depth " << depth << ", radius " << radius << " m, density "
                         << density << " kg/m³, height " << height << " m, ε " << restitution);
            const Bounce bounce = drop(mesh, cache, radius, depth, density, restitution, height);
            const float expected = restitution * restitution * bounce.fall;
            // The apex between two frames, and a tree's bumps tipping the ball a little: 5%.
            EXPECT_NEAR(bounce.climb, expected, 0.05f * expected);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace sphys::tools
