#include "bench_scene.h"

#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::compare {
namespace {

// The bunny's model from sphys: one body is enough, every bunny is the same.
BenchShape bunny_shape(const tools::Scene& scene) {
  tools::Scene one = scene;
  one.bodies.resize(1);
  one.joints.clear();
  tools::BuildWorldOptions build;
  build.cache_dir = tools::default_cache_dir();
  const tools::SimulationSetup setup = tools::build_world(one, build);
  const tools::BodyShape& built = setup.shapes.front();
  BenchShape shape;
  shape.name = "bunny";
  shape.mesh = *built.body_mesh;
  const RigidBody& body = setup.world->body(setup.bodies.front());
  shape.mass = body.mass();
  shape.inertia = body.inertia_body;
  shape.max_vertex_distance = static_cast<float>(built.max_vertex_distance);
  for (const std::uint32_t leaf : built.tree->leaves()) {
    shape.leaves.push_back(built.tree->sphere(leaf));
  }
  return shape;
}

}  // namespace

BenchScene bunny_bench_scene(std::string name, tools::Scene bunnies, int depth) {
  BenchScene bench;
  bench.name = std::move(name);
  bench.depth = depth;
  bench.scene = std::move(bunnies);
  bench.scene.ground.kind = tools::GroundSpec::Kind::kPlane;
  bench.scene.ground.height = 0.0;
  bench.scene.ground.restitution = bench.restitution;
  bench.scene.ground.friction = bench.friction;
  for (tools::BodySpec& body : bench.scene.bodies) {
    body.restitution = bench.restitution;
    body.friction = bench.friction;
  }
  bench.time_step = bench.scene.time_step;
  if (!bench.scene.bodies.empty()) bench.shapes.push_back(bunny_shape(bench.scene));
  for (const tools::BodySpec& spec : bench.scene.bodies) {
    bench.shape_of.push_back(0);
    bench.start.push_back(Transform{spec.orientation, spec.position});
  }
  return bench;
}

BenchScene make_bench_scene(int stacks, int per_stack, int depth) {
  return bunny_bench_scene(std::to_string(stacks) + "x" + std::to_string(per_stack),
                           tools::bunny_stacks_scene(stacks, per_stack, depth), depth);
}

}  // namespace sphys::compare
