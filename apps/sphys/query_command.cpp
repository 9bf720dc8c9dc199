// `sphys query`: one question asked of a scene's world (its bodies where the scene puts them, or
// after --frames steps): a ray cast, an overlap, a distance, or a robot's configuration or
// motion (robot_query.cpp), answered as JSON.

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "robot_query.h"
#include "sphys/error.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/tree_cache.h"
#include "sphys/world_query.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

struct QueryOptions {
  std::string scene;
  int frames = 0;
  std::vector<double> ray;  // origin then direction
  double max_distance = std::numeric_limits<double>::infinity();
  bool all = false;
  std::vector<double> sphere;          // centre, radius
  std::vector<double> aabb;            // low, high
  std::vector<double> box;             // centre, half extents
  std::vector<double> orientation;     // of --box, x y z w
  std::vector<std::int64_t> distance;  // two bodies
  std::vector<double> point_distance;  // a body, then a point
  std::vector<std::int64_t> skip;
  bool skip_sleeping = false;
  bool no_cache = false;
  RobotQueryOptions robot;
};

Vec3 vec3_at(const std::vector<double>& values, std::size_t first) {
  return {static_cast<float>(values[first]), static_cast<float>(values[first + 1]),
          static_cast<float>(values[first + 2])};
}

// The scene's bodies by their place in the scene file, and back.
class SceneBodies {
 public:
  explicit SceneBodies(const std::vector<BodyId>& bodies) : bodies_(bodies) {}
  [[nodiscard]] BodyId id(std::int64_t index, const std::string& option) const {
    if (index < 0 || static_cast<std::size_t>(index) >= bodies_.size()) {
      throw Error(option + ": no body " + std::to_string(index) + " in the scene (bodies 0.." +
                  std::to_string(static_cast<std::int64_t>(bodies_.size()) - 1) + ")");
    }
    return bodies_[static_cast<std::size_t>(index)];
  }
  // The body's place in the scene, or "ground" for the octree ground's static body.
  [[nodiscard]] nlohmann::json index(BodyId id) const {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (bodies_[i] == id) return i;
    }
    return "ground";
  }

 private:
  const std::vector<BodyId>& bodies_;
};

nlohmann::json vector_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json hit_json(const RayHit& hit, const SceneBodies& bodies) {
  return {{"body", bodies.index(hit.body)},
          {"leaf", hit.leaf},
          {"distance", hit.distance},
          {"point", vector_json(hit.point)},
          {"normal", vector_json(hit.normal)}};
}

nlohmann::json distance_json(const DistanceResult& r) {
  return {{"distance", r.distance},
          {"exact", r.exact},
          {"leaf_a", r.leaf_a},
          {"leaf_b", r.leaf_b},
          {"point_a", vector_json(r.point_a)},
          {"point_b", vector_json(r.point_b)},
          {"sphere_tests", r.sphere_tests}};
}

// The query's own sphys::Error, prefixed with the option that gave its input.
template <class Ask>
auto asked(const std::string& option, const Ask& ask) {
  try {
    return ask();
  } catch (const Error& error) {
    throw Error(option + ": " + error.what());
  }
}

void run(const QueryOptions& options) {
  const int questions = (options.ray.empty() ? 0 : 1) + (options.sphere.empty() ? 0 : 1) +
                        (options.aabb.empty() ? 0 : 1) + (options.box.empty() ? 0 : 1) +
                        (options.distance.empty() ? 0 : 1) +
                        (options.point_distance.empty() ? 0 : 1) +
                        (options.robot.urdf.empty() ? 0 : 1);
  if (questions != 1) {
    throw Error(
        "give exactly one of --ray, --sphere, --aabb, --box, --distance, "
        "--point-distance, --robot (got " +
        std::to_string(questions) + ")");
  }
  if (!options.orientation.empty() && options.box.empty()) {
    throw Error("--orientation: only with --box");
  }
  if (options.robot.urdf.empty()) check_robot_options_unused(options.robot);
  tools::Scene scene = tools::load_scene(options.scene);
  tools::BuildWorldOptions build;
  if (!options.no_cache) build.cache_dir = tools::default_cache_dir();
  const tools::SimulationSetup setup = tools::build_world(scene, build);
  World& world = *setup.world;
  for (int frame = 0; frame < options.frames; ++frame) {
    world.step(static_cast<float>(scene.time_step));
  }
  const SceneBodies bodies(setup.bodies);
  QueryFilter filter;
  for (const std::int64_t index : options.skip) filter.skip.push_back(bodies.id(index, "--skip"));
  filter.skip_sleeping = options.skip_sleeping;
  const WorldQuery query(world);

  nlohmann::json out = {{"scene", scene.name}, {"frames", options.frames}};
  const auto body_list = [&](const std::vector<BodyId>& ids) {
    nlohmann::json list = nlohmann::json::array();
    for (const BodyId id : ids) list.push_back(bodies.index(id));
    return list;
  };
  if (!options.robot.urdf.empty()) {
    out.update(robot_query(options.robot, query, filter, [&](std::int32_t slot) {
      return bodies.index(world.id_of(static_cast<std::uint32_t>(slot)));
    }));
  } else if (!options.ray.empty()) {
    const Ray ray{vec3_at(options.ray, 0), vec3_at(options.ray, 3),
                  static_cast<float>(options.max_distance)};
    out["query"] = "ray";
    if (options.all) {
      nlohmann::json hits = nlohmann::json::array();
      for (const RayHit& hit : asked("--ray", [&] { return query.cast_ray_all(ray, filter); })) {
        hits.push_back(hit_json(hit, bodies));
      }
      out["hits"] = hits;
    } else {
      const std::optional<RayHit> hit = asked("--ray", [&] { return query.cast_ray(ray, filter); });
      out["hit"] = hit ? hit_json(*hit, bodies) : nlohmann::json(nullptr);
    }
  } else if (!options.sphere.empty()) {
    out["query"] = "sphere";
    out["bodies"] = body_list(asked("--sphere", [&] {
      return query.overlap_sphere(vec3_at(options.sphere, 0), static_cast<float>(options.sphere[3]),
                                  filter);
    }));
  } else if (!options.aabb.empty()) {
    out["query"] = "aabb";
    out["bodies"] = body_list(asked("--aabb", [&] {
      return query.overlap_aabb({vec3_at(options.aabb, 0), vec3_at(options.aabb, 3)}, filter);
    }));
  } else if (!options.box.empty()) {
    OrientedBox box;
    box.pose.translation = vec3_at(options.box, 0);
    box.half_extents = vec3_at(options.box, 3);
    if (!options.orientation.empty()) {
      const std::vector<double>& q = options.orientation;
      box.pose.rotation = Quat(static_cast<float>(q[3]), static_cast<float>(q[0]),
                               static_cast<float>(q[1]), static_cast<float>(q[2]));
    }
    out["query"] = "box";
    out["bodies"] = body_list(asked("--box", [&] { return query.overlap_box(box, filter); }));
  } else if (!options.distance.empty()) {
    out["query"] = "distance";
    out["result"] = distance_json(asked("--distance", [&] {
      return query.distance(bodies.id(options.distance[0], "--distance"),
                            bodies.id(options.distance[1], "--distance"));
    }));
  } else {
    const double body = options.point_distance[0];
    if (body != std::floor(body)) {
      throw Error("--point-distance: the body must be a whole number, got " + std::to_string(body));
    }
    out["query"] = "point-distance";
    out["result"] = distance_json(asked("--point-distance", [&] {
      return query.distance(bodies.id(static_cast<std::int64_t>(body), "--point-distance"),
                            vec3_at(options.point_distance, 1));
    }));
  }
  print_output(out.dump(2) + "\n");
}

}  // namespace

void add_query_command(CLI::App& app) {
  auto options = std::make_shared<QueryOptions>();
  CLI::App* cmd = app.add_subcommand(
      "query",
      "Ask a scene's world one question without stepping it (or after --frames steps): a ray "
      "cast, an overlap, a distance, or whether a robot at joint values (or moving between two "
      "sets of them) is free, from the bodies' leaf spheres; JSON out. Bodies are "
      "numbered as the scene lists them, the octree ground is \"ground\", and the exact ground "
      "plane is no body");
  cmd->add_option("scene", options->scene, "A scene file (.json, see docs/scenes.md) or a preset")
      ->check(kFileName)
      ->required();
  cmd->add_option("--frames", options->frames, "Steps to take before asking (default 0)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--ray", options->ray, "OX OY OZ DX DY DZ: a ray's origin (m) and direction")
      ->expected(6);
  cmd->add_option("--max-distance", options->max_distance, "How far the ray reaches (m)");
  cmd->add_flag("--all", options->all, "Every body on the ray (nearest first), not the nearest");
  cmd->add_option("--sphere", options->sphere, "X Y Z R: bodies overlapping a sphere (m)")
      ->expected(4);
  cmd->add_option("--aabb", options->aabb,
                  "X0 Y0 Z0 X1 Y1 Z1: bodies overlapping an axis-aligned box (m)")
      ->expected(6);
  cmd->add_option("--box", options->box,
                  "CX CY CZ HX HY HZ: bodies overlapping a box of centre and half extents (m)")
      ->expected(6);
  cmd->add_option("--orientation", options->orientation, "QX QY QZ QW: the --box's rotation")
      ->expected(4);
  cmd->add_option("--distance", options->distance,
                  "A B: the smallest gap between two bodies' leaf spheres (m)")
      ->expected(2);
  cmd->add_option("--point-distance", options->point_distance,
                  "A X Y Z: the smallest gap between a body's leaf spheres and a point (m)")
      ->expected(4);
  cmd->add_option("--skip", options->skip, "Bodies the query leaves out")->expected(1, -1);
  cmd->add_flag("--skip-sleeping", options->skip_sleeping, "Leave sleeping bodies out");
  cmd->add_flag("--no-cache", options->no_cache, "Build sphere-trees even if they are cached");
  add_robot_query_options(*cmd, options->robot);
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
