// A robot's checks from joint values: the model's kinematics compiled into flat float tables,
// posed kPoseLanes configurations at a time by the widest kernel this processor runs, each
// configuration then checked by the ConfigurationChecker; motions as their states, coarse to fine.

#include "sphys/robot_check.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "query/configuration_layout.h"
#include "query/robot_kinematics.h"
#include "sphys/error.h"
#include "sphys/solver_settings.h"

namespace sphys {
namespace {

static_assert(RobotChecker::kPosedTogether == kPoseLanes);

// The most states one motion may be cut into: more is a resolution too fine for its length.
constexpr double kMostMotionStates = 1e7;
// Motions of up to this many states are posed whole and checked together. unit: states
constexpr std::uint32_t kStatesCheckedTogether = 256;

// The rows of a matrix, row-major, as the kernel reads them.
void put(const Eigen::Matrix3d& m, std::vector<float>& out) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(m(r, c)));
  }
}

void put(const Eigen::Vector3d& v, std::vector<float>& out) {
  for (int i = 0; i < 3; ++i) out.push_back(static_cast<float>(v[i]));
}

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& axis) {
  Eigen::Matrix3d k;
  k << 0.0, -axis.z(), axis.y(), axis.z(), 0.0, -axis.x(), -axis.y(), axis.x(), 0.0;
  return k;
}

std::vector<std::int32_t> sphere_links_of(const RobotModel& model) {
  check_robot_model(model);
  return model.sphere_links;
}

ConfigurationCheckSettings configuration_settings(const RobotModel& model,
                                                  const RobotCheckSettings& settings) {
  ConfigurationCheckSettings out;
  out.filter = settings.filter;
  out.self_collision = settings.self_collision;
  out.allowed_link_pairs = model.allowed_link_pairs;
  return out;
}

}  // namespace

struct RobotChecker::Compiled {
  std::vector<std::int32_t> parent;
  std::vector<std::int32_t> joint;
  std::vector<LinkMotion> motion;
  std::vector<float> a, b, c, t, d;
  std::vector<std::int32_t> sphere_link;
  std::vector<float> sphere;
  KinematicsTables tables;
  PoseBlock kernel = nullptr;
  const char* lanes = "portable";
};

struct RobotChecker::PoseScratch {
  explicit PoseScratch(const RobotModel& model)
      : values(model.joints.size()),
        links(model.links.size() * 12),
        posed(kPoseLanes * model.spheres.size() * kFloatsPerSphere) {}
  std::vector<PoseLane> values;  // per joint
  std::vector<PoseLane> links;   // per link, 12 lane vectors
  std::vector<float> posed;      // kPoseLanes configurations' spheres
};

RobotChecker::RobotChecker(const WorldQuery& query, RobotModel model, RobotCheckSettings settings)
    : model_(std::move(model)),
      checker_(query, sphere_links_of(model_), configuration_settings(model_, settings)),
      compiled_(std::make_unique<Compiled>()) {
  Compiled& k = *compiled_;
  for (std::size_t l = 0; l < model_.links.size(); ++l) {
    const RobotModel::Link& link = model_.links[l];
    const Eigen::Isometry3d origin = link.parent < 0 ? model_.base * link.origin : link.origin;
    const Eigen::Matrix3d rotation = origin.linear();
    k.parent.push_back(link.parent);
    k.joint.push_back(std::max(link.joint, 0));
    put(rotation, k.a);
    put(Eigen::Vector3d(origin.translation()), k.t);
    Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    LinkMotion motion = LinkMotion::kFixed;
    if (link.joint >= 0) {
      const RobotModel::Joint& joint = model_.joints[static_cast<std::size_t>(link.joint)];
      if (joint.type == RobotJointType::kPrismatic) {
        motion = LinkMotion::kSlide;
        d = rotation * joint.axis;
      } else {
        motion = LinkMotion::kTurn;
        const Eigen::Matrix3d cross = cross_matrix(joint.axis);
        b = rotation * cross;
        c = rotation * cross * cross;
      }
    }
    k.motion.push_back(motion);
    put(b, k.b);
    put(c, k.c);
    put(d, k.d);
  }
  for (std::size_t s = 0; s < model_.spheres.size(); ++s) {
    k.sphere_link.push_back(model_.sphere_links[s]);
    const Sphere& sphere = model_.spheres[s];
    k.sphere.insert(k.sphere.end(),
                    {sphere.center.x(), sphere.center.y(), sphere.center.z(), sphere.radius});
  }
  k.tables = {.links = static_cast<int>(model_.links.size()),
              .spheres = static_cast<int>(model_.spheres.size()),
              .parent = k.parent.data(),
              .joint = k.joint.data(),
              .motion = k.motion.data(),
              .a = k.a.data(),
              .b = k.b.data(),
              .c = k.c.data(),
              .t = k.t.data(),
              .d = k.d.data(),
              .sphere_link = k.sphere_link.data(),
              .sphere = k.sphere.data()};
  // The solver's choice of lanes (SPHYS_SIMD, else the widest the processor has): every kernel
  // gives the same bits, so it changes the speed only.
  switch (resolve_solver_lanes(SolverLanes::kAuto)) {
    case SolverLanes::kAvx2:
      k.kernel = avx2_pose_block();
      k.lanes = "avx2";
      break;
    case SolverLanes::kSse2:
      k.kernel = sse2_pose_block();
      k.lanes = "sse2";
      break;
    case SolverLanes::kAuto:
    case SolverLanes::kPortable:
      break;
  }
  if (k.kernel == nullptr) {
    k.kernel = portable_pose_block();
    k.lanes = "portable";
  }
}

RobotChecker::~RobotChecker() = default;

const char* RobotChecker::lanes() const { return compiled_->lanes; }

void RobotChecker::pose(const double* values, std::size_t count, float* out,
                        PoseScratch& scratch) const {
  const std::size_t joints = model_.joints.size();
  for (std::size_t j = 0; j < joints; ++j) {
    const RobotModel::Joint& joint = model_.joints[j];
    for (std::size_t i = 0; i < static_cast<std::size_t>(kPoseLanes); ++i) {
      // Lanes past `count` repeat the first configuration: posed, never read.
      const double value = values[(i < count ? i : 0) * joints + j];
      // Turning joints' values brought into [-pi, pi] in double (exactly, by std::remainder,
      // which leaves a value already there as it is), where the kernel's sine is accurate.
      const bool turned =
          joint.type != RobotJointType::kPrismatic && !(std::abs(value) <= std::numbers::pi);
      scratch.values[j].v[i] =
          static_cast<float>(turned ? std::remainder(value, 2.0 * std::numbers::pi) : value);
    }
  }
  compiled_->kernel(compiled_->tables, scratch.values.front().v, scratch.links.front().v,
                    scratch.posed.data());
  std::copy_n(scratch.posed.begin(), count * model_.spheres.size() * kFloatsPerSphere, out);
}

namespace {

// Throws sphys::Error naming the configuration and joint of the first value that is NaN,
// infinite or outside its joint's limits.
void check_values(const RobotModel& model, std::span<const double> values, const char* what) {
  const std::size_t joints = model.joints.size();
  if (joints == 0 ? !values.empty() : values.size() % joints != 0) {
    throw Error(std::string(what) + ": " + std::to_string(values.size()) +
                " values is no whole number of configurations of " + std::to_string(joints) +
                " joints");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const RobotModel::Joint& joint = model.joints[i % joints];
    const double value = values[i];
    if (!std::isfinite(value) || value < joint.lower || value > joint.upper) {
      throw Error(std::string(what) + ": configuration " + std::to_string(i / joints) +
                  ", joint '" + joint.name + "': " + std::to_string(value) +
                  (std::isfinite(value) ? " is outside its limits " + std::to_string(joint.lower) +
                                              " .. " + std::to_string(joint.upper)
                                        : " is not finite"));
    }
  }
}

}  // namespace

void RobotChecker::pose_spheres(std::span<const double> values, std::span<float> spheres) const {
  check_values(model_, values, "values");
  const std::size_t joints = model_.joints.size();
  const std::size_t count = joints == 0 ? 0 : values.size() / joints;
  const std::size_t per = model_.spheres.size() * kFloatsPerSphere;
  if (spheres.size() != count * per) {
    throw Error("spheres: " + std::to_string(spheres.size()) + " floats for " +
                std::to_string(count) + " configurations of " +
                std::to_string(model_.spheres.size()) + " spheres × 4");
  }
  PoseScratch scratch(model_);
  for (std::size_t first = 0; first < count; first += kPoseLanes) {
    const std::size_t n = std::min<std::size_t>(kPoseLanes, count - first);
    pose(values.data() + first * joints, n, spheres.data() + first * per, scratch);
  }
}

void RobotChecker::check(std::span<const double> values, std::span<ConfigurationResult> results,
                         const Parallel* parallel) const {
  check_values(model_, values, "values");
  const std::size_t joints = model_.joints.size();
  const std::size_t count = joints == 0 ? 0 : values.size() / joints;
  if (results.size() != count) {
    throw Error("results: " + std::to_string(results.size()) + " entries for " +
                std::to_string(count) + " configurations");
  }
  const std::size_t per = model_.spheres.size() * kFloatsPerSphere;
  const auto run = [&](std::size_t begin, std::size_t end) {
    PoseScratch scratch(model_);
    ConfigurationChecker::Run checks(checker_);
    std::vector<float> posed(kPoseLanes * per);
    for (std::size_t first = begin; first < end; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, end - first);
      pose(values.data() + first * joints, n, posed.data(), scratch);
      for (std::size_t i = 0; i < n; ++i) results[first + i] = checks.check(posed.data() + i * per);
    }
  };
  if (parallel == nullptr) {
    run(0, count);
  } else {
    parallel->for_each_run(count, kConfigurationsPerRun, run);
  }
}

namespace {

// The order in which a motion's `states` states are checked: both ends, then the midpoints of
// ever finer halves, breadth first, so that a collision anywhere along it is met early.
std::vector<std::uint32_t> coarse_to_fine(std::uint32_t states) {
  std::vector<std::uint32_t> order = {0};
  if (states > 1) order.push_back(states - 1);
  std::vector<std::array<std::uint32_t, 2>> spans = {{0, states - 1}};
  std::vector<std::array<std::uint32_t, 2>> finer;
  while (!spans.empty()) {
    finer.clear();
    for (const auto& [low, high] : spans) {
      if (high - low < 2) continue;
      const std::uint32_t middle = low + (high - low) / 2;
      order.push_back(middle);
      finer.push_back({low, middle});
      finer.push_back({middle, high});
    }
    spans.swap(finer);
  }
  return order;
}

}  // namespace

MotionResult RobotChecker::check_motion(std::span<const double> from, std::span<const double> to,
                                        double resolution) const {
  const std::size_t joints = model_.joints.size();
  if (from.size() != joints || to.size() != joints) {
    throw Error("a motion needs " + std::to_string(joints) + " joint values at each end, got " +
                std::to_string(from.size()) + " and " + std::to_string(to.size()));
  }
  check_values(model_, from, "from");
  check_values(model_, to, "to");
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("resolution must be positive and finite, got " + std::to_string(resolution));
  }
  double length = 0.0;
  for (std::size_t j = 0; j < joints; ++j) length += (to[j] - from[j]) * (to[j] - from[j]);
  length = std::sqrt(length);
  const double steps = std::ceil(length / resolution);
  if (steps + 1.0 > kMostMotionStates) {
    throw Error("resolution " + std::to_string(resolution) + " cuts a motion of length " +
                std::to_string(length) + " into more than " +
                std::to_string(static_cast<long long>(kMostMotionStates)) + " states");
  }
  MotionResult result;
  result.states = static_cast<std::uint32_t>(std::max(1.0, steps)) + 1;
  const std::uint32_t last = result.states - 1;
  const auto state = [&](std::uint32_t k, double* out) {
    const double along = static_cast<double>(k) / last;
    for (std::size_t j = 0; j < joints; ++j) {
      // The ends exactly, and every state between them within both ends' limits.
      out[j] = k == last ? to[j]
                         : std::clamp(from[j] + (to[j] - from[j]) * along, model_.joints[j].lower,
                                      model_.joints[j].upper);
    }
  };
  const std::size_t per = model_.spheres.size() * kFloatsPerSphere;
  PoseScratch scratch(model_);
  ConfigurationChecker::Run checks(checker_);
  const std::vector<std::uint32_t> order = coarse_to_fine(result.states);
  std::vector<double> values(kPoseLanes * joints);
  // A motion of few states is posed whole and its states checked together (each link's groups
  // collected once, for the bound of all its states); a longer one a block of states at a time.
  const bool together = result.states <= kStatesCheckedTogether;
  std::vector<float> posed((together ? result.states : kPoseLanes) * per);
  if (together) {
    for (std::uint32_t first = 0; first < result.states; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, result.states - first);
      for (std::size_t i = 0; i < n; ++i) {
        state(first + static_cast<std::uint32_t>(i), values.data() + i * joints);
      }
      pose(values.data(), n, posed.data() + first * per, scratch);
    }
    checks.gather(posed.data(), result.states);
  }
  // Checks `count` states, in order: the position of the first that collides (its answer in
  // result.collision), else -1.
  const auto check_states = [&](const std::uint32_t* states, std::size_t count) {
    for (std::size_t first = 0; first < count; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, count - first);
      if (!together) {
        for (std::size_t i = 0; i < n; ++i) state(states[first + i], values.data() + i * joints);
        pose(values.data(), n, posed.data(), scratch);
      }
      for (std::size_t i = 0; i < n; ++i) {
        const ConfigurationResult answer = together ? checks.check_gathered(states[first + i])
                                                    : checks.check(posed.data() + i * per);
        if (!answer.free) {
          result.collision = answer;
          return static_cast<std::int64_t>(first + i);
        }
      }
    }
    return std::int64_t{-1};
  };
  const std::int64_t hit = check_states(order.data(), order.size());
  if (hit < 0) return result;
  // The states before the one found, those not checked yet, in order: the first that collides.
  const std::uint32_t found = order[static_cast<std::size_t>(hit)];
  std::vector<std::uint8_t> checked(found, 0);
  for (std::int64_t i = 0; i < hit; ++i) {
    if (order[static_cast<std::size_t>(i)] < found) checked[order[static_cast<std::size_t>(i)]] = 1;
  }
  std::vector<std::uint32_t> before;
  for (std::uint32_t k = 0; k < found; ++k) {
    if (checked[k] == 0) before.push_back(k);
  }
  const ConfigurationResult at_found = result.collision;
  const std::int64_t earlier = check_states(before.data(), before.size());
  const std::uint32_t first = earlier < 0 ? found : before[static_cast<std::size_t>(earlier)];
  if (earlier < 0) result.collision = at_found;
  result.free = false;
  result.first_collision = static_cast<std::int32_t>(first);
  result.last_free = first == 0 ? 0.0 : static_cast<double>(first - 1) / last;
  return result;
}

void RobotChecker::check_motions(std::span<const double> from, std::span<const double> to,
                                 double resolution, std::span<MotionResult> results,
                                 const Parallel* parallel) const {
  const std::size_t joints = model_.joints.size();
  if (from.size() != to.size() || from.size() != results.size() * joints) {
    throw Error("motions: " + std::to_string(from.size()) + " and " + std::to_string(to.size()) +
                " values for " + std::to_string(results.size()) + " motions of " +
                std::to_string(joints) + " joints");
  }
  const auto one = [&](std::size_t m) {
    results[m] =
        check_motion(from.subspan(m * joints, joints), to.subspan(m * joints, joints), resolution);
  };
  if (parallel == nullptr) {
    for (std::size_t m = 0; m < results.size(); ++m) one(m);
  } else {
    parallel->for_each(results.size(), one);
  }
}

}  // namespace sphys
