#pragma once

// `sphys query --robot`: a robot at joint values, or its straight motion between two sets of
// them, checked against the scene's world (RobotChecker), answered as JSON.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sphys/world_query.h"

namespace sphys::cli {

struct RobotQueryOptions {
  std::string urdf;
  std::string spheres_from;  // the spheres `sphys spherize` wrote
  std::string srdf;          // its disable_collisions, for --self-collision
  std::vector<std::string> packages;
  std::vector<double> base;             // x y z (m), then the rotation qx qy qz qw
  std::vector<std::string> joints, to;  // NAME=VALUE (rad or m)
  double resolution = 0.01;             // of a motion's states. unit: rad and m
  bool self_collision = false;
  int tree_depth = 0;  // 0: the world's. unit: levels
};

// The options above on `query`.
void add_robot_query_options(CLI::App& query, RobotQueryOptions& options);
// Throws sphys::Error naming the robot's options given without --robot.
void check_robot_options_unused(const RobotQueryOptions& options);

// The robot's answer: at --joint's values, or along the motion from them to --to's. `body_index`
// gives a world body slot as the scene numbers it.
[[nodiscard]] nlohmann::json robot_query(
    const RobotQueryOptions& options, const WorldQuery& query, const QueryFilter& filter,
    const std::function<nlohmann::json(std::int32_t slot)>& body_index);

}  // namespace sphys::cli
