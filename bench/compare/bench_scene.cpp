#include "bench_scene.h"

#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::compare {

BenchScene make_bench_scene(int stacks, int per_stack, int depth) {
  BenchScene bench;
  bench.stacks = stacks;
  bench.per_stack = per_stack;
  bench.depth = depth;
  bench.scene = tools::bunny_stacks_scene(stacks, per_stack, depth);
  bench.scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  bench.scene.ground.height = 0.0;
  bench.scene.ground.restitution = bench.restitution;
  bench.scene.ground.friction = bench.friction;
  for (tools::BodySpec& body : bench.scene.bodies) {
    body.restitution = bench.restitution;
    body.friction = bench.friction;
  }
  bench.time_step = bench.scene.time_step;

  // One body is enough for the model: every bunny is the same.
  tools::Scene one = bench.scene;
  one.bodies.resize(1);
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  const tools::SimulationSetup setup = tools::build_world(one, build);
  const tools::BodyShape& shape = setup.shapes.front();
  bench.mesh = *shape.body_mesh;
  const RigidBody& body = setup.world->body(setup.bodies.front());
  bench.mass = body.mass();
  bench.inertia = body.inertia_body;
  bench.max_vertex_distance = static_cast<float>(shape.max_vertex_distance);
  for (const std::uint32_t leaf : shape.tree->leaves()) {
    bench.leaves.push_back(shape.tree->sphere(leaf));
  }
  for (const tools::BodySpec& spec : bench.scene.bodies) {
    bench.start.push_back(Transform{spec.orientation, spec.position});
  }
  return bench;
}

}  // namespace sphys::compare
