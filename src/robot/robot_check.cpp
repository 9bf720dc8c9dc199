// A robot's checks from joint values: the model's kinematics compiled into flat float tables,
// posed kPoseLanes configurations at a time by the widest kernel this processor runs, each
// configuration then checked by the ConfigurationChecker (motions: robot_motion.cpp).

#include "sphys/robot_check.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>

#include "core/simd_lanes.h"
#include "robot/configuration_layout.h"
#include "robot/robot_kinematics.h"
#include "robot/robot_pose_scratch.h"
#include "sphys/error.h"

namespace sphys {
namespace {

static_assert(RobotChecker::kPosedTogether == kPoseLanes);

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

// The ball about the base's place that every sphere of the robot stays in, whatever its joint
// values: each link's frame lies no farther from it than its parent's plus its origin's offset
// (and a sliding joint's longest travel); rotations keep distances.
Sphere robot_reach(const RobotModel& model) {
  std::vector<double> farthest(model.links.size(), 0.0);  // each link's frame. unit: m
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    double far = (link.parent < 0 ? 0.0 : farthest[static_cast<std::size_t>(link.parent)]) +
                 link.origin.translation().norm();
    if (link.joint >= 0) {
      const RobotModel::Joint& joint = model.joints[static_cast<std::size_t>(link.joint)];
      if (joint.type == RobotJointType::kPrismatic) {
        far += std::max(std::abs(joint.lower), std::abs(joint.upper));
      }
    }
    farthest[l] = far;
  }
  double reach = 0.0;
  for (std::size_t s = 0; s < model.spheres.size(); ++s) {
    const Sphere& sphere = model.spheres[s];
    reach = std::max(reach, farthest[static_cast<std::size_t>(model.sphere_links[s])] +
                                sphere.center.cast<double>().norm() + sphere.radius);
  }
  // Against the float kinematics' rounding: a thousandth more, and a millimetre.
  return {model.base.translation().cast<float>(), static_cast<float>(reach * 1.001 + 1e-3)};
}

ConfigurationCheckSettings configuration_settings(const RobotModel& model,
                                                  const RobotCheckSettings& settings) {
  ConfigurationCheckSettings out;
  out.reach = robot_reach(model);
  out.filter = settings.filter;
  out.self_collision = settings.self_collision;
  out.allowed_link_pairs = model.allowed_link_pairs;
  out.tree_depth = settings.tree_depth;
  return out;
}

}  // namespace

RobotChecker::RobotChecker(const WorldQuery& query, RobotModel model, RobotCheckSettings settings)
    : model_(std::move(model)),
      checker_(query, sphere_links_of(model_), configuration_settings(model_, settings)),
      compiled_(std::make_unique<Compiled>(model_)) {
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
  for (const RobotModel::Joint& joint : model_.joints) {
    k.lower.push_back(joint.lower);
    k.upper.push_back(joint.upper);
  }
  for (std::size_t s = 0; s < model_.spheres.size(); ++s) {
    k.sphere_link.push_back(model_.sphere_links[s]);
    const Sphere& sphere = model_.spheres[s];
    k.sphere.insert(k.sphere.end(),
                    {sphere.center.x(), sphere.center.y(), sphere.center.z(), sphere.radius});
  }
  for (std::size_t l = 0; l < model_.links.size(); ++l) {
    k.link_first.push_back(static_cast<std::uint32_t>(k.link_spheres.size()));
    Aabb box;
    for (std::size_t s = 0; s < model_.spheres.size(); ++s) {
      if (static_cast<std::size_t>(model_.sphere_links[s]) != l) continue;
      k.link_spheres.push_back(static_cast<std::uint32_t>(s));
      box.extend(Aabb::around_sphere(model_.spheres[s].center, model_.spheres[s].radius));
    }
    const Vec3 centre = box.empty() ? Vec3::Zero() : box.center();
    const Vec3 half = box.empty() ? Vec3::Zero() : Vec3(0.5f * (box.max - box.min));
    k.link_centre.insert(k.link_centre.end(), {centre.x(), centre.y(), centre.z()});
    k.link_centre_size.insert(k.link_centre_size.end(),
                              {std::abs(centre.x()), std::abs(centre.y()), std::abs(centre.z())});
    k.link_half.insert(k.link_half.end(), {half.x(), half.y(), half.z()});
  }
  k.link_first.push_back(static_cast<std::uint32_t>(k.link_spheres.size()));
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
              .sphere = k.sphere.data(),
              .boxed_links = static_cast<int>(checker_.links()),
              .box_centre = k.link_centre.data(),
              .box_centre_size = k.link_centre_size.data(),
              .box_half = k.link_half.data()};
  const Sphere reach = robot_reach(model_);
  k.sweep_margin = 1e-4f * (reach.center.norm() + reach.radius);
  // The library's choice of lanes (SPHYS_SIMD, else the widest the processor has): every kernel
  // gives the same bits, so it changes the speed only.
  SolverLanes lanes = choose_lanes(SolverLanes::kAuto, avx2_kernel().pose != nullptr);
  switch (lanes) {
    case SolverLanes::kAvx2:
      k.kernel = avx2_kernel();
      break;
    case SolverLanes::kSse2:
      k.kernel = sse2_kernel();
      break;
    case SolverLanes::kAuto:
    case SolverLanes::kPortable:
      break;
  }
  if (k.kernel.pose == nullptr) {
    k.kernel = portable_kernel();
    lanes = SolverLanes::kPortable;
  }
  k.lanes = kLaneSetNames[static_cast<std::size_t>(lanes)].data();  // literals: NUL-terminated
}

RobotChecker::~RobotChecker() = default;

std::unique_ptr<RobotChecker::Workspace> RobotChecker::take_workspace() const {
  {
    const std::lock_guard lock(workspaces_mutex_);
    if (!workspaces_.empty()) {
      // The one this thread used last, if kept: its buffers are still in this core's caches,
      // where another thread's would have to be fetched from the other core's line by line.
      const auto mine = std::ranges::find_if(
          workspaces_, [](const auto& kept) { return kept->thread == std::this_thread::get_id(); });
      if (mine != workspaces_.end()) std::swap(*mine, workspaces_.back());
      std::unique_ptr<Workspace> kept = std::move(workspaces_.back());
      workspaces_.pop_back();
      return kept;
    }
  }
  return std::make_unique<Workspace>(*this);
}

void RobotChecker::keep_workspace(std::unique_ptr<Workspace> workspace) const {
  workspace->thread = std::this_thread::get_id();
  const std::lock_guard lock(workspaces_mutex_);
  workspaces_.push_back(std::move(workspace));
}

const char* RobotChecker::lanes() const { return compiled_->lanes; }

const float* RobotChecker::pose(const double* values, std::size_t count, PoseScratch& scratch,
                                bool with_spheres) const {
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
  // The links' boxes where the spheres are not all placed: those of links near a body are.
  compiled_->kernel.pose(compiled_->tables, scratch.values.front().v, scratch.links.front().v,
                         with_spheres ? nullptr : scratch.boxes.front().v,
                         with_spheres ? scratch.posed.data() : nullptr);
  return scratch.posed.data();
}

void RobotChecker::place_near_spheres(const float* links, std::size_t lane,
                                      const ConfigurationChecker::Run& checks,
                                      float* spheres) const {
  const Compiled& k = *compiled_;
  constexpr auto W = static_cast<std::size_t>(kPoseLanes);
  // As the kernel places them: the same products added in the same order, so the same bits.
  for (std::size_t l = 0; l < checker_.links(); ++l) {
    if (!checks.near(l)) continue;
    // The link's pose in this lane, read once (the spheres written could alias the poses).
    std::array<float, 12> p;
    for (std::size_t i = 0; i < 12; ++i) p[i] = links[(12 * l + i) * W + lane];
    for (std::uint32_t i = k.link_first[l]; i < k.link_first[l + 1]; ++i) {
      const std::uint32_t s = k.link_spheres[i];
      const float* local = &k.sphere[4 * s];
      float* out = spheres + kFloatsPerSphere * s;
      for (std::size_t r = 0; r < 3; ++r) {
        out[r] = p[3 * r] * local[0] + p[3 * r + 1] * local[1] + p[3 * r + 2] * local[2] + p[9 + r];
      }
      out[3] = local[3];
    }
  }
}

ConfigurationResult RobotChecker::check_from_links(std::size_t lane, Workspace& workspace) const {
  workspace.checks.bound(workspace.pose.boxes.front().v + lane, kPoseLanes);
  float* spheres = workspace.pose.posed.data();
  place_near_spheres(workspace.pose.links.front().v, lane, workspace.checks, spheres);
  return workspace.checks.check_bounded(spheres);
}

void RobotChecker::pose_spheres(std::span<const double> values, std::span<float> spheres) const {
  check_joint_values(model_, values, "values");
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
    std::copy_n(pose(values.data() + first * joints, n, scratch), n * per,
                spheres.data() + first * per);
  }
}

bool RobotChecker::within_limits(const double* values, std::size_t count) const {
  const std::size_t joints = model_.joints.size();
  const double* lower = compiled_->lower.data();
  const double* upper = compiled_->upper.data();
  // No branch per value: v - v is 0 for a finite v alone, and NaN fails every comparison.
  bool inside = true;
  for (std::size_t c = 0; c < count; ++c) {
    const double* configuration = values + c * joints;
    for (std::size_t j = 0; j < joints; ++j) {
      const double v = configuration[j];
      inside &= (v >= lower[j]) & (v <= upper[j]) & (v - v == 0.0);
    }
  }
  return inside;
}

void RobotChecker::check(std::span<const double> values, std::span<ConfigurationResult> results,
                         const Parallel* parallel) const {
  const std::size_t joints = model_.joints.size();
  if (joints == 0 ? !values.empty() : values.size() % joints != 0) {
    check_joint_values(model_, values, "values");  // names the sizes
  }
  const std::size_t count = joints == 0 ? 0 : values.size() / joints;
  if (results.size() != count) {
    throw Error("results: " + std::to_string(results.size()) + " entries for " +
                std::to_string(count) + " configurations");
  }
  const std::size_t per = model_.spheres.size() * kFloatsPerSphere;
  // The first run of configurations with a value outside its limits, if any: each run checks its
  // own values, so that the check runs on the threads too.
  std::atomic<std::size_t> first_refused{count};
  const auto run = [&](std::size_t begin, std::size_t end) {
    if (!within_limits(values.data() + begin * joints, end - begin)) {
      std::size_t first = first_refused.load();
      while (begin < first && !first_refused.compare_exchange_weak(first, begin)) {
      }
      return;
    }
    std::unique_ptr<Workspace> workspace = take_workspace();
    // Self-collision reads every sphere: each configuration posed whole. Else the links' poses
    // alone, each link bounded from its pose and only the spheres of links near a body placed.
    const bool whole = checker_.reads_every_sphere();
    for (std::size_t first = begin; first < end; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, end - first);
      const float* posed = pose(values.data() + first * joints, n, workspace->pose, whole);
      for (std::size_t i = 0; i < n; ++i) {
        results[first + i] =
            whole ? workspace->checks.check(posed + i * per) : check_from_links(i, *workspace);
      }
    }
    keep_workspace(std::move(workspace));
  };
  const std::size_t runs = (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun;
  for_each_on(parallel, runs, [&](std::size_t r) {
    run(r * kConfigurationsPerRun, std::min(count, (r + 1) * kConfigurationsPerRun));
  });
  const std::size_t refused = first_refused.load();
  if (refused < count) {
    // Every configuration before that run's is within its limits: this names its first refused.
    check_joint_values(
        model_, values.first(std::min(count, refused + kConfigurationsPerRun) * joints), "values");
  }
}

}  // namespace sphys
