#include "engine.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::compare {
namespace {

class SphysEngine final : public Engine {
 public:
  SphysEngine(const BenchScene& bench, bool paper, std::uint32_t threads,
              std::optional<BroadPhaseKind> broad_phase)
      : dt_(static_cast<float>(bench.time_step)) {
    tools::Scene scene = bench.scene;
    if (paper) scene.response = ResponseMode::kPaper;
    tools::BuildWorldOptions build;
    build.cache_dir = tools::default_cache_dir();
    build.threads = threads;
    build.broad_phase = broad_phase;
    // The deepest penetration the comparison prints for every engine.
    build.plausibility_figures = true;
    setup_ = tools::build_world(scene, build);
    // The bodies the tools::Scene does not hold (limbs), from their shapes' trees.
    for (std::size_t b = setup_.bodies.size(); b < bench.start.size(); ++b) {
      const BenchShape& shape = bench.shape(b);
      BodyDesc desc;
      desc.tree = shape.tree;
      desc.pose = bench.start[b];
      desc.mass = shape.mass;
      desc.inertia = shape.inertia;
      desc.restitution = bench.restitution;
      desc.friction = bench.friction;
      setup_.bodies.push_back(setup_.world->add_body(desc));
    }
    for (const tools::JointSpec& joint : bench.joints) {
      JointDesc desc = joint.desc;
      desc.body_a = joint.body_a ? setup_.bodies[*joint.body_a] : BodyId{};
      desc.body_b = joint.body_b ? setup_.bodies[*joint.body_b] : BodyId{};
      setup_.world->add_joint(desc);
      ++joints_;
    }
  }

  void step() override { stats_ = setup_.world->step(dt_); }

  void read(std::vector<BodyState>& out) const override {
    out.clear();
    for (const BodyId id : setup_.bodies) {
      const RigidBody& body = setup_.world->body(id);
      out.push_back({body.pose, body.linear_velocity, body.angular_velocity});
    }
  }

  [[nodiscard]] std::uint32_t contacts() const override { return stats_.contacts; }
  [[nodiscard]] std::uint32_t joints() const override { return joints_; }
  [[nodiscard]] float deepest_penetration() const override { return stats_.deepest_penetration; }
  [[nodiscard]] std::optional<std::uint32_t> asleep() const override {
    return stats_.bodies_asleep;
  }

 private:
  float dt_;
  tools::SimulationSetup setup_;
  StepStats stats_;
  std::uint32_t joints_ = 0;  // added to the world
};

}  // namespace

std::unique_ptr<Engine> make_sphys_engine(const BenchScene& scene, bool paper,
                                          std::uint32_t threads,
                                          std::optional<BroadPhaseKind> broad_phase) {
  return std::make_unique<SphysEngine>(scene, paper, threads, broad_phase);
}

}  // namespace sphys::compare
