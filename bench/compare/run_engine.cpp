#include "run_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "peak_memory.h"

namespace sphys::compare {
namespace {

// The scene's measures at the end: |v| + |ω| r_max above this is moving. unit: m/s
constexpr float kMovingSpeed = 0.01f;
// A body whose centre of mass is below this has fallen through the plane. unit: m
constexpr float kBelowPlane = -0.5f;

using BodyPair = std::pair<std::size_t, std::size_t>;  // smaller index, larger

BodyPair ordered(std::size_t a, std::size_t b) { return {std::min(a, b), std::max(a, b)}; }

// Pairs of bodies that collide in no engine, sorted: joined bodies, and the robot's pairs kept
// apart.
std::vector<BodyPair> apart_pairs(const BenchScene& scene) {
  std::vector<BodyPair> pairs;
  for (const tools::JointSpec& joint : scene.joints) {
    if (joint.body_a && joint.body_b) pairs.push_back(ordered(*joint.body_a, *joint.body_b));
  }
  if (scene.robot) {
    for (const auto& [a, b] : scene.robot->apart) pairs.push_back(ordered(a, b));
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// The deepest leaf-sphere overlap between bodies that may collide, or of a moving body with the
// plane y = 0, at these poses: bodies are swept along x by their bounding spheres, then every leaf
// pair of a close pair is tested.
float deepest_overlap(const BenchScene& scene, const std::vector<BodyState>& bodies) {
  float reach = 0.0f;  // of a leaf sphere from the centre of mass. unit: m
  for (const BenchShape& shape : scene.shapes) {
    for (const Sphere& leaf : shape.leaves) {
      reach = std::max(reach, leaf.center.norm() + leaf.radius);
    }
  }
  const std::vector<BodyPair> apart = apart_pairs(scene);
  std::vector<std::vector<Sphere>> placed(bodies.size());
  float deepest = 0.0f;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    // The robot's root stands fixed on the plane, which it meets in no engine.
    const bool on_plane = !(scene.robot && b == scene.robot->first_body);
    for (const Sphere& leaf : scene.shape(b).leaves) {
      const Sphere world{bodies[b].pose.apply(leaf.center), leaf.radius};
      if (on_plane) deepest = std::max(deepest, world.radius - world.center.y());
      placed[b].push_back(world);
    }
  }
  std::vector<std::size_t> order(bodies.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto x = [&](std::size_t b) { return bodies[b].pose.translation.x(); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x(a) < x(b); });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t a = order[i];
    for (std::size_t j = i + 1; j < order.size() && x(order[j]) - x(a) <= 2.0f * reach; ++j) {
      const std::size_t b = order[j];
      if ((bodies[a].pose.translation - bodies[b].pose.translation).norm() > 2.0f * reach) continue;
      if (std::binary_search(apart.begin(), apart.end(), ordered(a, b))) continue;
      for (const Sphere& p : placed[a]) {
        for (const Sphere& q : placed[b]) {
          deepest = std::max(deepest, p.radius + q.radius - (p.center - q.center).norm());
        }
      }
    }
  }
  return deepest;
}

// The largest distance between a joint's two anchor points at these poses, across a slider's
// axis (along it, the distance is the slider's position). unit: m
float largest_gap(const BenchScene& scene, const std::vector<BodyState>& bodies) {
  float largest = 0.0f;
  for (const tools::JointSpec& joint : scene.joints) {
    const Transform frame_a = joint.body_a ? bodies[*joint.body_a].pose : Transform{};
    const Vec3 a = frame_a.apply(joint.desc.anchor_a);
    const Vec3 b =
        joint.body_b ? bodies[*joint.body_b].pose.apply(joint.desc.anchor_b) : joint.desc.anchor_b;
    Vec3 gap = b - a;
    if (joint.desc.type == JointType::kSlider) {
      const Vec3 axis = frame_a.rotation * joint.desc.axis_a;
      gap -= gap.dot(axis) * axis;
    }
    largest = std::max(largest, gap.norm());
  }
  return largest;
}

// Adds how far the robot's joints are after a step from the targets that step was given to
// `result`'s largest errors, and their turning joints' errors to `turn_errors` (unit: rad).
void add_tracking(const BenchRobot& robot, const std::vector<double>& positions,
                  const std::vector<double>& targets, RunResult& result, double& turn_errors) {
  for (std::size_t j = 0; j < positions.size(); ++j) {
    const double error = std::abs(positions[j] - targets[j]);
    if (robot.model.joints[j].type == RobotJointType::kPrismatic) {
      result.largest_slide_error = std::max(result.largest_slide_error, error);
    } else {
      result.largest_turn_error = std::max(result.largest_turn_error, error);
      turn_errors += error;
    }
  }
}

}  // namespace

RunResult run_engine(const std::string& name, const BenchScene& scene, int frames,
                     double time_limit) {
  const PeakMemory memory;
  const std::unique_ptr<Engine> engine = make_engine(name, scene);
  RunResult result;
  result.step_ms.reserve(static_cast<std::size_t>(frames));
  double contacts = 0.0;
  double step_seconds = 0.0;  // the step times summed. unit: s
  // The deepest penetration of the last second's frames run, oldest overwritten first.
  std::vector<float> last_second(
      static_cast<std::size_t>(std::max(1.0, std::round(1.0 / scene.time_step))), 0.0f);
  double turn_errors = 0.0;             // summed over the turning joints and the frames. unit: rad
  std::optional<MotionSteps> expected;  // the robot's targets, step by step
  if (scene.robot) expected.emplace(scene.robot->motion, scene.time_step);
  std::vector<BodyState> bodies;
  for (int frame = 0; frame < frames; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    engine->step();
    const auto end = std::chrono::steady_clock::now();
    result.step_ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    step_seconds += std::chrono::duration<double>(end - start).count();
    contacts += engine->contacts();
    const float deepest = engine->deepest_penetration();
    result.deepest = std::max(result.deepest, deepest);
    last_second[static_cast<std::size_t>(frame) % last_second.size()] = deepest;
    if (expected) {
      expected->next();
      add_tracking(*scene.robot, engine->robot_positions(), expected->positions(), result,
                   turn_errors);
    }
    if (!scene.joints.empty()) {  // read outside the step's time
      engine->read(bodies);
      result.largest_gap = std::max(result.largest_gap, largest_gap(scene, bodies));
    }
    if (time_limit > 0.0 && step_seconds > time_limit && frame + 1 < frames) {
      result.stopped = true;
      break;
    }
  }
  const auto frames_run = static_cast<double>(result.step_ms.size());
  result.contacts_per_step = frames_run > 0.0 ? contacts / frames_run : 0.0;
  if (scene.robot && frames_run > 0.0) {
    const auto turning = std::ranges::count_if(scene.robot->model.joints, [](const auto& joint) {
      return joint.type != RobotJointType::kPrismatic;
    });
    result.mean_turn_error = turn_errors / (frames_run * static_cast<double>(turning));
  }
  result.deepest_last_second = *std::max_element(last_second.begin(), last_second.end());
  result.peak_memory_mib = memory.added_mib();
  engine->read(bodies);
  result.bodies = static_cast<std::uint32_t>(bodies.size());
  result.joints = engine->joints();
  result.largest_gap_at_end = largest_gap(scene, bodies);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyState& body = bodies[b];
    const BenchShape& shape = scene.shape(b);
    const Mat3 rotation = body.pose.rotation.toRotationMatrix();
    const Mat3 inertia = rotation * shape.inertia * rotation.transpose();
    result.kinetic_energy += 0.5 * shape.mass * body.linear_velocity.squaredNorm() +
                             0.5 * body.angular_velocity.dot(inertia * body.angular_velocity);
    const float speed =
        body.linear_velocity.norm() + body.angular_velocity.norm() * shape.max_vertex_distance;
    result.moving += speed > kMovingSpeed ? 1 : 0;
    result.below += body.pose.translation.y() < kBelowPlane ? 1 : 0;
  }
  result.end_overlap = deepest_overlap(scene, bodies);
  result.asleep = engine->asleep();
  result.warnings = engine->warnings();
  return result;
}

}  // namespace sphys::compare
