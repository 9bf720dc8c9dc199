#include "robot_query.h"

#include <cmath>
#include <optional>

#include "joint_option.h"
#include "sphys/error.h"
#include "sphys/robot_check.h"
#include "sphys/tools/robot_model_file.h"

namespace sphys::cli {
namespace {

// The robot's model from its files, at --base.
RobotModel robot_model_of(const RobotQueryOptions& options) {
  std::vector<tools::RobotPackage> packages;
  for (const std::string& package : options.packages) {
    packages.push_back(tools::parse_robot_package(package));
  }
  std::optional<std::filesystem::path> srdf;
  if (!options.srdf.empty()) srdf = options.srdf;
  RobotModel model = tools::load_robot_model(options.urdf, options.spheres_from, packages, srdf);
  if (!options.base.empty()) {
    const std::vector<double>& b = options.base;
    for (const double value : b) {
      if (!std::isfinite(value)) throw Error("--base: every value must be finite");
    }
    const Eigen::Quaterniond rotation(b[6], b[3], b[4], b[5]);
    if (std::abs(rotation.norm() - 1.0) > 1e-3) {
      throw Error("--base: the rotation QX QY QZ QW is not a unit quaternion (norm " +
                  std::to_string(rotation.norm()) + ")");
    }
    model.base = Eigen::Isometry3d::Identity();
    model.base.translate(Eigen::Vector3d(b[0], b[1], b[2]));
    model.base.rotate(rotation.normalized());
  }
  return model;
}

}  // namespace

void add_robot_query_options(CLI::App& query, RobotQueryOptions& options) {
  query.add_option("--robot", options.urdf,
                   "ROBOT.urdf: whether the robot at --joint's values (or moving to --to's) is "
                   "free of the bodies");
  query.add_option("--spheres-from", options.spheres_from,
                   "The robot's spheres, as `sphys spherize` wrote them (cuRobo YAML, SRDF or a "
                   "spherized URDF)");
  query.add_option("--package", options.packages,
                   "NAME=DIR: where the URDF's package://NAME/ paths point (repeatable)");
  query.add_option("--srdf", options.srdf,
                   "An SRDF whose disable_collisions pairs --self-collision leaves out");
  query
      .add_option("--base", options.base,
                  "X Y Z QX QY QZ QW: the robot's base in the world (m, unit quaternion)")
      ->expected(7);
  query.add_option("--joint", options.joints,
                   "NAME=VALUE: a joint's value (rad or m; repeatable; joints not given are 0)");
  query.add_option("--to", options.to,
                   "NAME=VALUE: the motion's end (repeatable; joints not given keep --joint's)");
  query.add_option("--resolution", options.resolution,
                   "The most a motion's states are apart: the norm of the joint values' change "
                   "(rad and m; default 0.01)");
  query.add_flag("--self-collision", options.self_collision,
                 "Check the robot's links against each other too");
  query.add_option("--tree-depth", options.tree_depth,
                   "--robot: levels of the bodies' trees to check at, deeper than the world's "
                   "(0, the default: the world's)");
}

void check_robot_options_unused(const RobotQueryOptions& options) {
  const RobotQueryOptions none;
  const bool given = !options.spheres_from.empty() || !options.srdf.empty() ||
                     !options.packages.empty() || !options.base.empty() ||
                     !options.joints.empty() || !options.to.empty() ||
                     options.resolution != none.resolution || options.self_collision ||
                     options.tree_depth != none.tree_depth;
  if (given) {
    throw Error(
        "--spheres-from, --srdf, --package, --base, --joint, --to, --resolution, "
        "--self-collision and --tree-depth: only with --robot");
  }
}

nlohmann::json robot_query(const RobotQueryOptions& options, const WorldQuery& query,
                           const QueryFilter& filter,
                           const std::function<nlohmann::json(std::int32_t slot)>& body_index) {
  if (options.spheres_from.empty()) throw Error("--robot: give its spheres with --spheres-from");
  const RobotModel model = robot_model_of(options);
  std::vector<double> from(model.joints.size(), 0.0);
  set_joint_values(model, "--joint", options.joints, from);
  check_joint_values(model, from, "--joint");
  RobotCheckSettings settings;
  settings.filter = filter;
  settings.self_collision = options.self_collision;
  settings.tree_depth = options.tree_depth;
  const RobotChecker checker = [&] {
    try {
      return RobotChecker(query, model, settings);
    } catch (const Error& error) {
      throw Error(std::string("--robot: ") + error.what());
    }
  }();
  const auto collision_json = [&](const ConfigurationResult& r) {
    if (r.free) return nlohmann::json(nullptr);
    const auto link_of = [&](std::int32_t sphere) {
      const auto link = model.sphere_links[static_cast<std::size_t>(sphere)];
      return model.links[static_cast<std::size_t>(link)].name;
    };
    nlohmann::json out = {{"sphere", r.sphere}, {"link", link_of(r.sphere)}};
    if (r.body >= 0) out["body"] = body_index(r.body);
    if (r.other_sphere >= 0) {
      out["other_sphere"] = r.other_sphere;
      out["other_link"] = link_of(r.other_sphere);
    }
    return out;
  };
  nlohmann::json joints = nlohmann::json::array();
  for (const RobotModel::Joint& joint : model.joints) joints.push_back(joint.name);
  nlohmann::json out = {{"robot", model.name}, {"joints", joints}, {"from", from}};
  if (options.to.empty()) {
    std::vector<ConfigurationResult> result(1);
    checker.check(from, result);
    out["query"] = "robot";
    out["free"] = result[0].free;
    out["collision"] = collision_json(result[0]);
    return out;
  }
  std::vector<double> to = from;
  set_joint_values(model, "--to", options.to, to);
  check_joint_values(model, to, "--to");
  const MotionResult motion = [&] {
    try {
      return checker.check_motion(from, to, options.resolution);
    } catch (const Error& error) {
      throw Error(std::string("--resolution: ") + error.what());
    }
  }();
  out["query"] = "robot-motion";
  out["to"] = to;
  out["resolution"] = options.resolution;
  out["free"] = motion.free;
  out["states"] = motion.states;
  out["first_collision"] = motion.first_collision;
  out["last_free"] = motion.last_free;
  out["collision"] = collision_json(motion.collision);
  return out;
}

}  // namespace sphys::cli
