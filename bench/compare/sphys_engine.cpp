#include <optional>

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
    // The bodies the tools::Scene does not hold (limbs), from their shapes' trees, and the joints
    // between them; the robot makes its own.
    const std::size_t shaped = bench.robot ? bench.robot->first_body : bench.start.size();
    const std::size_t joined = bench.robot ? bench.robot->first_joint : bench.joints.size();
    for (std::size_t b = setup_.bodies.size(); b < shaped; ++b) {
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
    for (std::size_t j = 0; j < joined; ++j) {
      const tools::JointSpec& joint = bench.joints[j];
      JointDesc desc = joint.desc;
      desc.body_a = joint.body_a ? setup_.bodies[*joint.body_a] : BodyId{};
      desc.body_b = joint.body_b ? setup_.bodies[*joint.body_b] : BodyId{};
      setup_.world->add_joint(desc);
      ++joints_;
    }
    if (bench.robot) add_robot(*bench.robot);
  }

  void step() override {
    if (targets_) {
      targets_->next();
      for (std::size_t j = 0; j < controls_.size(); ++j) {
        controls_[j].target_position = targets_->positions()[j];
        controls_[j].target_velocity = targets_->speeds()[j];
      }
      setup_.world->set_robot_controls(robot_id_, controls_);
    }
    stats_ = setup_.world->step(dt_);
  }

  [[nodiscard]] std::vector<double> robot_positions() const override {
    return targets_ ? setup_.world->robot_joint_states(robot_id_).positions : std::vector<double>{};
  }

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
  // The robot at its motion's start, every joint under position control with the scene's gains.
  void add_robot(const BenchRobot& robot) {
    targets_.emplace(robot.motion, double{dt_});
    robot_id_ = setup_.world->add_robot(robot.model, robot.base);
    setup_.world->set_robot_configuration(robot_id_, robot.motion.waypoints.front());
    const std::span<const BodyId> bodies = setup_.world->robot_bodies(robot_id_);
    setup_.bodies.insert(setup_.bodies.end(), bodies.begin(), bodies.end());
    joints_ += static_cast<std::uint32_t>(setup_.world->robot_joints(robot_id_).size());
    controls_.assign(robot.model.joints.size(), robot.gains);
    for (RobotJointControl& control : controls_) control.mode = RobotControlMode::kPosition;
  }

  float dt_;
  tools::SimulationSetup setup_;
  StepStats stats_;
  std::uint32_t joints_ = 0;  // added to the world
  RobotId robot_id_;
  std::vector<RobotJointControl> controls_;  // per joint, set before each step
  std::optional<MotionSteps> targets_;       // the robot's, step by step; none without one
};

}  // namespace

std::unique_ptr<Engine> make_sphys_engine(const BenchScene& scene, bool paper,
                                          std::uint32_t threads,
                                          std::optional<BroadPhaseKind> broad_phase) {
  return std::make_unique<SphysEngine>(scene, paper, threads, broad_phase);
}

}  // namespace sphys::compare
