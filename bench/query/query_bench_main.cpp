// sphys-query-bench: sphys's queries beside Bullet's rayTest and contactTest and FCL's collide
// on the same worlds in the same run, alternating block by block (docs/queries.md):
// - ray casts in a heap of resting bunnies (depth-2 trees), against Bullet on the same spheres;
// - batched configuration checks of the spherized test robot by a pile of bunnies, against FCL
//   on the robot's link meshes and the bunnies' meshes, with the agreement of the answers, and
//   against Bullet's contactTest of the robot's spheres with the same sphere compounds;
// - the same checks on two threads against one;
// - distances between two bunnies at random poses, against a loop over every leaf pair.
// Times are per query, each read with steady_clock; the table gives medians and their ratios.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include <CLI/CLI.hpp>

#include "other_engines.h"
#include "robot_arm/bunny_pile.h"
#include "robot_arm/robot_arm.h"
#include "sphys/configuration_check.h"
#include "sphys/error.h"
#include "sphys/robot_check.h"
#include "sphys/tools/median.h"
#include "sphys/tools/robot_model_file.h"
#include "sphys/tools/sph_file.h"
#include "sphys/tools/spherize.h"
#include "sphys/world_query.h"
#include "support/test_robot.h"

namespace sphys::query_bench {
namespace {

using Clock = std::chrono::steady_clock;
using Rng = std::mt19937;
using tools::median;

// The checks' pile: its bunnies' trees are built to kCheckTreeDepth levels, of which the world
// uses kCheckLevelsUsed, as a simulation of it would; the checks may ask the deeper ones.
constexpr int kCheckTreeDepth = 4;   // unit: levels
constexpr int kCheckLevelsUsed = 2;  // unit: levels

struct Options {
  int ray_stacks = 100;   // × 10 bunnies
  int check_stacks = 10;  // × 10 bunnies, settled by --write-check-pile
  std::filesystem::path check_pile = examples::kept_bunny_pile();
  int rays = 20000;
  int configurations = 100000;
  int fcl_configurations = 10000;
  int distance_pairs = 2000;
  int spheres = 60;
  int block = 1000;  // queries per engine before the other takes its turn
};

double microseconds(Clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

float uniform(Rng& rng, float low, float high) {
  return std::uniform_real_distribution<float>(low, high)(rng);
}

void rays(const Options& options) {
  const examples::BunnyPile heap = examples::settle_bunny_pile(options.ray_stacks, 10, 900);
  const WorldQuery query(*heap.setup.world);
  const BulletScene bullet(heap.leaves, heap.poses, {});
  Rng rng(1);
  // From above the heap down to a random point in it, through the heap's top layers.
  constexpr float kLength = 100.0f;  // unit: m
  std::vector<Ray> all;
  for (int i = 0; i < options.rays; ++i) {
    const Aabb& b = heap.bounds;
    const Vec3 target(uniform(rng, b.min.x(), b.max.x()), uniform(rng, b.min.y(), b.max.y()),
                      uniform(rng, b.min.z(), b.max.z()));
    const Vec3 origin(uniform(rng, b.min.x(), b.max.x()), b.max.y() + 1.0f,
                      uniform(rng, b.min.z(), b.max.z()));
    all.push_back({origin, (target - origin).normalized(), kLength});
  }
  std::vector<double> sphys_us;
  std::vector<double> bullet_us;
  std::vector<std::optional<RayHit>> ours(all.size());
  std::vector<BulletScene::Hit> theirs(all.size());
  for (std::size_t begin = 0; begin < all.size(); begin += options.block) {
    const std::size_t end = std::min(all.size(), begin + options.block);
    for (std::size_t i = begin; i < end; ++i) {
      const auto start = Clock::now();
      ours[i] = query.cast_ray(all[i]);
      sphys_us.push_back(microseconds(Clock::now() - start));
    }
    for (std::size_t i = begin; i < end; ++i) {
      const auto start = Clock::now();
      theirs[i] = bullet.cast(all[i].origin, all[i].direction, kLength);
      bullet_us.push_back(microseconds(Clock::now() - start));
    }
  }
  std::size_t hits = 0;
  std::size_t hit_or_miss_agree = 0;
  std::size_t both_hit = 0;
  std::size_t same_body = 0;
  std::size_t within_mm = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    hits += ours[i] ? 1 : 0;
    const bool bullet_hit = theirs[i].body >= 0;
    hit_or_miss_agree += ours[i].has_value() == bullet_hit ? 1 : 0;
    if (!ours[i] || !bullet_hit) continue;
    ++both_hit;
    same_body +=
        ours[i]->body == heap.setup.bodies[static_cast<std::size_t>(theirs[i].body)] ? 1 : 0;
    within_mm += std::abs(ours[i]->distance - theirs[i].distance) < 1e-3f ? 1 : 0;
  }
  const double ours_median = median(sphys_us);
  const double theirs_median = median(bullet_us);
  std::printf("\n## Ray casts: closest hit, %zu bunnies at rest (%d frames), %zu rays\n\n",
              heap.poses.size(), heap.frames, all.size());
  std::printf("| engine | median µs/ray | ratio to sphys |\n| --- | --- | --- |\n");
  std::printf("| sphys WorldQuery::cast_ray | %.3f | 1.00 |\n", ours_median);
  std::printf("| Bullet rayTest (sphere compounds) | %.3f | %.2f |\n", theirs_median,
              theirs_median / ours_median);
  std::printf(
      "\nRays that hit: %.1f%%. Bullet agrees on hit or miss for %.2f%% of the rays; "
      "where both hit, on the body for %.2f%% and on the distance within 1 mm for %.2f%%.\n",
      100.0 * double(hits) / double(all.size()),
      100.0 * double(hit_or_miss_agree) / double(all.size()),
      100.0 * double(same_body) / double(both_hit), 100.0 * double(within_mm) / double(both_hit));
}

// Random joint values within the limits (N × J, the arm's joint order), posed: N × S × 4 spheres
// and N × L link poses.
struct Configurations {
  std::vector<double> values;
  std::vector<float> spheres;
  std::vector<Transform> link_poses;
};

Configurations random_configurations(const examples::RobotArm& arm, int count, Rng& rng) {
  Configurations out;
  out.spheres.resize(static_cast<std::size_t>(count) * arm.spheres() * 4);
  out.link_poses.resize(static_cast<std::size_t>(count) * arm.links.size());
  std::vector<double> values(arm.joints.size());
  for (int c = 0; c < count; ++c) {
    for (std::size_t j = 0; j < values.size(); ++j) {
      values[j] = std::uniform_real_distribution<double>(arm.limits[j][0], arm.limits[j][1])(rng);
    }
    out.values.insert(out.values.end(), values.begin(), values.end());
    const auto n = static_cast<std::size_t>(c);
    arm.link_poses(values,
                   std::span(out.link_poses).subspan(n * arm.links.size(), arm.links.size()));
    arm.posed_spheres(values,
                      std::span(out.spheres).subspan(n * arm.spheres() * 4, arm.spheres() * 4));
  }
  return out;
}

// The arm as a RobotModel: its URDF's chain with the links' spheres, standing where the arm does.
RobotModel arm_model(const examples::RobotArm& arm) {
  RobotModel model = tools::robot_model(arm.robot, arm.links);
  model.base = Eigen::Isometry3d::Identity();
  model.base.translate(arm.base.translation.cast<double>());
  model.base.rotate(arm.base.rotation.cast<double>());
  return model;
}

// Configurations of the arm's joint values (its order) in the model's joint order.
std::vector<double> in_model_order(const examples::RobotArm& arm, const RobotModel& model,
                                   const std::vector<double>& values) {
  const std::size_t joints = model.joints.size();
  std::vector<double> out(values.size());
  for (std::size_t j = 0; j < joints; ++j) {
    const auto at = static_cast<std::size_t>(std::ranges::find(arm.joints, model.joints[j].name) -
                                             arm.joints.begin());
    for (std::size_t c = 0; c * joints < out.size(); ++c) {
      out[c * joints + j] = values[c * joints + at];
    }
  }
  return out;
}

// The checks' world: the pile, the arm beside it and its random configurations.
struct CheckScene {
  examples::BunnyPile heap;
  examples::RobotArm arm;
  std::unique_ptr<WorldQuery> query;
  Configurations configurations;
};

CheckScene make_check_scene(const Options& options) {
  CheckScene scene;
  scene.heap = examples::read_bunny_pile(options.check_pile, kCheckTreeDepth, kCheckLevelsUsed);
  // The robot's files, written for the run and removed after it.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sphys-query-bench-" + std::to_string(getpid()));
  scene.arm = examples::make_test_robot_arm(dir, options.spheres, Vec3::Zero());
  std::filesystem::remove_all(dir);
  scene.query = std::make_unique<WorldQuery>(*scene.heap.setup.world);
  // At the pile's side, on the plane: many of its reaches end in a bunny.
  examples::place_arm_beside(scene.arm, *scene.query, scene.heap.bounds.center(), 0.05f);
  Rng rng(2);
  scene.configurations = random_configurations(scene.arm, options.configurations, rng);
  return scene;
}

void configuration_checks(const Options& options) {
  const CheckScene scene = make_check_scene(options);
  const examples::BunnyPile& heap = scene.heap;
  const examples::RobotArm& arm = scene.arm;
  const WorldQuery& query = *scene.query;
  const Configurations& configurations = scene.configurations;
  const ConfigurationChecker checker(query, arm.sphere_links);
  // From joint values: the arm's model, its kinematics and check in one call,
  // RobotChecker::kPosedTogether configurations a call, the values in the model's joint order.
  const RobotModel model = arm_model(arm);
  const RobotChecker robot_checker(query, model);
  // The same from the bunnies' deeper levels, below the world's leaves a sphere touches.
  struct DeeperLevel {
    int depth;
    std::unique_ptr<RobotChecker> checker;
    std::vector<ConfigurationResult> results;
    std::vector<double> us;  // per configuration, of a call for kPosedTogether of them
  };
  std::vector<DeeperLevel> deeper;
  for (int depth = kCheckLevelsUsed + 1; depth <= kCheckTreeDepth; ++depth) {
    RobotCheckSettings settings;
    settings.tree_depth = depth;
    deeper.push_back({depth,
                      std::make_unique<RobotChecker>(query, model, settings),
                      std::vector<ConfigurationResult>(options.configurations),
                      {}});
  }
  const std::size_t joints = model.joints.size();
  const std::vector<double> model_values = in_model_order(arm, model, configurations.values);
  const FclScene fcl(heap.mesh(), heap.poses, arm.link_meshes());
  std::vector<float> robot_radii;
  for (const Sphere& sphere : arm.link_spheres) robot_radii.push_back(sphere.radius);
  const BulletScene bullet(heap.leaves, heap.poses, robot_radii);

  const std::size_t per = arm.spheres() * 4;
  const std::size_t count = static_cast<std::size_t>(options.configurations);
  // FCL takes every k-th block, so that it sees fcl_configurations of them.
  const std::size_t blocks = (count + options.block - 1) / options.block;
  const std::size_t fcl_every =
      std::max<std::size_t>(1, blocks * options.block / std::max(1, options.fcl_configurations));
  std::vector<ConfigurationResult> results(count);
  std::vector<ConfigurationResult> from_values(count);
  std::vector<double>
      from_values_us;  // per configuration, of a call for RobotChecker::kPosedTogether of them
  std::vector<double> from_values_on_fcl_us;
  std::vector<double> sphys_us;
  std::vector<double> sphys_on_fcl_us;
  std::vector<double> fcl_us;
  std::vector<double> bullet_us;
  std::size_t bullet_agrees = 0;
  std::size_t both_hit = 0, both_free = 0, spheres_only = 0, mesh_only = 0;
  std::vector<std::pair<std::size_t, bool>> fcl_hit;  // FCL's configurations and answers
  for (std::size_t block = 0; block < blocks; ++block) {
    const std::size_t begin = block * options.block;
    const std::size_t end = std::min(count, begin + options.block);
    const bool with_fcl = block % fcl_every == 0;
    for (std::size_t c = begin; c < end; ++c) {
      const auto start = Clock::now();
      checker.check(std::span(configurations.spheres).subspan(c * per, per),
                    std::span(results).subspan(c, 1));
      const double us = microseconds(Clock::now() - start);
      sphys_us.push_back(us);
      if (with_fcl) sphys_on_fcl_us.push_back(us);
    }
    for (std::size_t c = begin; c < end; c += RobotChecker::kPosedTogether) {
      const std::size_t n = std::min<std::size_t>(RobotChecker::kPosedTogether, end - c);
      const auto start = Clock::now();
      robot_checker.check(std::span(model_values).subspan(c * joints, n * joints),
                          std::span(from_values).subspan(c, n));
      const double us = microseconds(Clock::now() - start) / static_cast<double>(n);
      from_values_us.push_back(us);
      if (with_fcl) from_values_on_fcl_us.push_back(us);
    }
    for (DeeperLevel& level : deeper) {
      for (std::size_t c = begin; c < end; c += RobotChecker::kPosedTogether) {
        const std::size_t n = std::min<std::size_t>(RobotChecker::kPosedTogether, end - c);
        const auto start = Clock::now();
        level.checker->check(std::span(model_values).subspan(c * joints, n * joints),
                             std::span(level.results).subspan(c, n));
        level.us.push_back(microseconds(Clock::now() - start) / static_cast<double>(n));
      }
    }
    if (!with_fcl) continue;
    for (std::size_t c = begin; c < end; ++c) {
      const auto start = Clock::now();
      const bool mesh_hit = fcl.collides(
          std::span(configurations.link_poses).subspan(c * arm.links.size(), arm.links.size()));
      fcl_us.push_back(microseconds(Clock::now() - start));
      const bool sphere_hit = !results[c].free;
      const auto bullet_start = Clock::now();
      const bool bullet_hit =
          bullet.touches(std::span(configurations.spheres).subspan(c * per, per));
      bullet_us.push_back(microseconds(Clock::now() - bullet_start));
      bullet_agrees += bullet_hit == sphere_hit ? 1 : 0;
      fcl_hit.emplace_back(c, mesh_hit);
      both_hit += sphere_hit && mesh_hit ? 1 : 0;
      both_free += !sphere_hit && !mesh_hit ? 1 : 0;
      spheres_only += sphere_hit && !mesh_hit ? 1 : 0;
      mesh_only += !sphere_hit && mesh_hit ? 1 : 0;
    }
  }
  std::size_t colliding = 0;
  std::size_t values_agree = 0;
  for (std::size_t c = 0; c < count; ++c) {
    colliding += results[c].free ? 0 : 1;
    values_agree += results[c].free == from_values[c].free ? 1 : 0;
  }

  // Motions of 32 states from the configurations, each joint moved by up to 0.1 (rad or m): the
  // free ones' check_motion against one configuration's check from joint values.
  constexpr std::uint32_t kMotionStates = 32;
  std::vector<double> free_motion_us;
  std::size_t motions = 0;
  {
    Rng motion_rng(5);
    std::vector<double> to(joints);
    for (std::size_t c = 0; c < count && free_motion_us.size() < 20000; ++c) {
      const std::span<const double> from = std::span(model_values).subspan(c * joints, joints);
      double length = 0.0;
      bool inside = true;
      for (std::size_t j = 0; j < joints; ++j) {
        to[j] = from[j] + std::uniform_real_distribution<double>(-0.1, 0.1)(motion_rng);
        inside = inside && to[j] >= model.joints[j].lower && to[j] <= model.joints[j].upper;
        length += (to[j] - from[j]) * (to[j] - from[j]);
      }
      if (!inside) continue;
      // Just over length / 31, so that rounding cannot make it 33 states.
      const double resolution = std::sqrt(length) / (kMotionStates - 1) * (1.0 + 1e-9);
      const auto start = Clock::now();
      const MotionResult motion = robot_checker.check_motion(from, to, resolution);
      const double us = microseconds(Clock::now() - start);
      ++motions;
      if (motion.free && motion.states == kMotionStates) free_motion_us.push_back(us);
    }
  }

  // Threads: the whole batch at once, one thread then two, alternating; from posed spheres and
  // from joint values. Eleven runs each: a run is tens of milliseconds, and a shared machine's
  // neighbours move single runs by a fifth.
  constexpr int kThreadRuns = 11;
  std::vector<double> one_ms;
  std::vector<double> two_ms;
  std::vector<double> values_one_ms;
  std::vector<double> values_two_ms;
  const Parallel two(2);
  for (int run = 0; run < kThreadRuns; ++run) {
    for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &two}) {
      auto start = Clock::now();
      checker.check(configurations.spheres, results, parallel);
      (parallel == nullptr ? one_ms : two_ms).push_back(microseconds(Clock::now() - start) / 1e3);
      start = Clock::now();
      robot_checker.check(model_values, from_values, parallel);
      (parallel == nullptr ? values_one_ms : values_two_ms)
          .push_back(microseconds(Clock::now() - start) / 1e3);
    }
  }

  const double fcl_n = double(fcl_us.size());
  std::printf(
      "\n## Batched configuration checks: the test robot (%zu spheres, %zu links) by "
      "%zu bunnies at rest, %zu random configurations (%.1f%% colliding)\n\n",
      arm.spheres(), arm.links.size(), heap.poses.size(), count,
      100.0 * double(colliding) / double(count));
  std::printf(
      "| engine | configurations | median µs/configuration | ratio to sphys |\n"
      "| --- | --- | --- | --- |\n");
  std::printf("| sphys ConfigurationChecker::check | %zu | %.3f | 1.00 |\n", count,
              median(sphys_us));
  std::printf("| sphys, FCL's configurations | %zu | %.3f | 1.00 |\n", sphys_on_fcl_us.size(),
              median(sphys_on_fcl_us));
  std::printf(
      "| sphys RobotChecker::check from joint values, kinematics included (%s lanes, %d a call) "
      "| %zu | %.3f | %.2f |\n",
      robot_checker.lanes(), RobotChecker::kPosedTogether,
      from_values_us.size() * RobotChecker::kPosedTogether, median(from_values_us),
      median(from_values_us) / median(sphys_on_fcl_us));
  std::printf("| sphys RobotChecker::check, FCL's configurations | %zu | %.3f | %.2f |\n",
              from_values_on_fcl_us.size() * RobotChecker::kPosedTogether,
              median(from_values_on_fcl_us),
              median(from_values_on_fcl_us) / median(sphys_on_fcl_us));
  std::printf("| FCL 0.7 collide (link meshes vs bunny meshes, OBBRSS) | %zu | %.3f | %.1f |\n",
              fcl_us.size(), median(fcl_us), median(fcl_us) / median(sphys_on_fcl_us));
  std::printf(
      "| Bullet contactTest (the robot's spheres vs sphere compounds) | %zu | %.3f | %.1f |\n",
      bullet_us.size(), median(bullet_us), median(bullet_us) / median(sphys_on_fcl_us));
  std::printf(
      "\nBullet, on the same spheres, agrees with sphys on %.2f%% of these "
      "configurations.\n",
      100.0 * double(bullet_agrees) / fcl_n);
  std::printf(
      "\nMotions of %u states (each joint moved by up to 0.1 from a configuration above): %zu "
      "free of %zu, check_motion's median %.3f µs, %.2f× one configuration's check from joint "
      "values (%.3f µs); its 90th percentile %.3f µs, %.2f×.\n",
      kMotionStates, free_motion_us.size(), motions, median(free_motion_us),
      median(free_motion_us) / median(from_values_us), median(from_values_us),
      tools::quantile(free_motion_us, 0.9),
      tools::quantile(free_motion_us, 0.9) / median(from_values_us));
  std::printf(
      "\nFCL from joint values: %.3f µs a configuration against sphys's %.3f, %.1f× (the FCL row "
      "leaves out FCL's kinematics, which the caller computes: the link poses here come from "
      "tools::link_poses in double). From joint values and from posed spheres sphys agrees on "
      "%.3f%% of all configurations (float against double kinematics).\n",
      median(fcl_us), median(from_values_on_fcl_us), median(fcl_us) / median(from_values_on_fcl_us),
      100.0 * double(values_agree) / double(count));
  std::printf(
      "\nAgreement on FCL's %zu configurations: both say the same %.2f%% (both collide "
      "%.2f%%, both free %.2f%%); spheres collide where the meshes are free (the cost of "
      "conservatism) %.2f%%; spheres free where the meshes collide %.2f%%.\n",
      fcl_us.size(), 100.0 * double(both_hit + both_free) / fcl_n, 100.0 * double(both_hit) / fcl_n,
      100.0 * double(both_free) / fcl_n, 100.0 * double(spheres_only) / fcl_n,
      100.0 * double(mesh_only) / fcl_n);
  std::printf(
      "\nThreads, the whole batch of %zu: one thread %.1f ms, two threads %.1f ms "
      "(medians of %d alternating runs): %.2f× on two; from joint values, one thread %.1f ms, "
      "two threads %.1f ms: %.2f× on two\n",
      count, median(one_ms), median(two_ms), kThreadRuns, median(one_ms) / median(two_ms),
      median(values_one_ms), median(values_two_ms), median(values_one_ms) / median(values_two_ms));

  // The levels: what each costs and how often its spheres collide where the meshes are free.
  std::printf(
      "\n### The bunnies' levels (trees of %d levels, the world using %d; from joint values)\n\n"
      "| levels | colliding | median µs/configuration | ratio to %d levels | FCL's "
      "configurations: spheres collide, meshes free | spheres free, meshes collide |\n"
      "| --- | --- | --- | --- | --- | --- |\n",
      kCheckTreeDepth, kCheckLevelsUsed, kCheckLevelsUsed);
  const auto level_row = [&](int depth, const std::vector<ConfigurationResult>& answers,
                             const std::vector<double>& us) {
    std::size_t hits = 0;
    for (const ConfigurationResult& r : answers) hits += r.free ? 0 : 1;
    std::size_t only_spheres = 0;
    std::size_t only_mesh = 0;
    for (const auto& [c, mesh_hit] : fcl_hit) {
      only_spheres += !answers[c].free && !mesh_hit ? 1 : 0;
      only_mesh += answers[c].free && mesh_hit ? 1 : 0;
    }
    std::printf("| %d | %.1f%% | %.3f | %.2f | %.2f%% | %.2f%% |\n", depth,
                100.0 * double(hits) / double(count), median(us),
                median(us) / median(from_values_us), 100.0 * double(only_spheres) / fcl_n,
                100.0 * double(only_mesh) / fcl_n);
  };
  level_row(kCheckLevelsUsed, from_values, from_values_us);
  for (const DeeperLevel& level : deeper) level_row(level.depth, level.results, level.us);
}

void distances(const Options& options) {
  const examples::BunnyPile one = examples::settle_bunny_pile(1, 1, 0);
  const auto tree = one.setup.shapes.front().tree;
  World world;
  Rng rng(3);
  std::vector<std::pair<BodyId, BodyId>> pairs;
  for (int i = 0; i < options.distance_pairs; ++i) {
    // Every pair about the origin (a distance query reads its two bodies alone, and far from
    // the origin float positions would round by more than the answers' tolerance); within a
    // pair, 0.7 to 1.6 m between the centres of mass.
    const Vec3 cell = Vec3::Zero();
    BodyDesc a;
    a.tree = tree;
    a.is_static = true;
    a.pose.rotation = Quat::UnitRandom();
    a.pose.translation = cell;
    BodyDesc b = a;
    b.pose.rotation = Quat::UnitRandom();
    const Vec3 direction = Vec3::Random().normalized();
    b.pose.translation = cell + uniform(rng, 0.7f, 1.6f) * direction;
    pairs.emplace_back(world.add_body(a), world.add_body(b));
  }
  const WorldQuery query(world);
  const std::vector<std::uint32_t> leaves = tree->leaves();
  std::vector<double> us;
  double worst_error = 0.0;
  std::size_t overlapping = 0;
  for (const auto& [a, b] : pairs) {
    const auto start = Clock::now();
    const DistanceResult result = query.distance(a, b);
    us.push_back(microseconds(Clock::now() - start));
    // The oracle: every leaf pair, in double.
    const Transform pa = world.body(a).pose;
    const Transform pb = world.body(b).pose;
    double best = INFINITY;
    for (const std::uint32_t la : leaves) {
      for (const std::uint32_t lb : leaves) {
        // Placed as the query places them: rotation matrix, then translation.
        const Vec3 ca = pa.rotation.toRotationMatrix() * tree->sphere(la).center + pa.translation;
        const Vec3 cb = pb.rotation.toRotationMatrix() * tree->sphere(lb).center + pb.translation;
        best = std::min(best, (ca.cast<double>() - cb.cast<double>()).norm() -
                                  tree->sphere(la).radius - tree->sphere(lb).radius);
      }
    }
    worst_error = std::max(worst_error, std::abs(best - result.distance));
    overlapping += result.distance < 0.0f ? 1 : 0;
  }
  std::printf(
      "\n## Distance between two bunnies (depth 2, %zu leaves each), %zu random pairs "
      "(%.1f%% overlapping)\n\n",
      leaves.size(), pairs.size(), 100.0 * double(overlapping) / double(pairs.size()));
  std::printf(
      "| engine | median µs/query | largest difference from every leaf pair (m) |\n"
      "| --- | --- | --- |\n");
  std::printf("| sphys WorldQuery::distance | %.3f | %.2g |\n", median(us), worst_error);
}

// What bench/query_python_bench.py times Python's world.check_configurations against: the
// checks' world and configurations written to `dir` (the bunny's tree as .sph, the bunnies'
// poses and the configurations as raw float32, the spheres' links as int32), and the C++ loop
// over them on one thread, kReferenceRuns times (a batch of 10,000 takes about a millisecond
// from joint values, within a shared machine's noise).
constexpr int kReferenceRuns = 21;

void python_reference(const Options& options, const std::filesystem::path& dir) {
  const CheckScene scene = make_check_scene(options);
  std::filesystem::create_directories(dir);
  tools::write_sph(dir / "bunny.sph",
                   scene.heap.setup.shapes.front().tree->truncated(kCheckLevelsUsed));
  const auto write = [&](const std::string& name, const void* data, std::size_t bytes) {
    std::ofstream out(dir / name, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
    if (!out) throw Error(name + ": cannot write in " + dir.string());
  };
  std::vector<float> poses;  // x y z, then the quaternion's x y z w
  for (const Transform& pose : scene.heap.poses) {
    const Quat& q = pose.rotation;
    poses.insert(poses.end(), {pose.translation.x(), pose.translation.y(), pose.translation.z(),
                               q.x(), q.y(), q.z(), q.w()});
  }
  write("poses.f32", poses.data(), poses.size() * sizeof(float));
  write("spheres.f32", scene.configurations.spheres.data(),
        scene.configurations.spheres.size() * sizeof(float));
  write("links.i32", scene.arm.sphere_links.data(),
        scene.arm.sphere_links.size() * sizeof(std::int32_t));
  const ConfigurationChecker checker(*scene.query, scene.arm.sphere_links);
  std::vector<ConfigurationResult> results(scene.configurations.spheres.size() /
                                           (scene.arm.spheres() * 4));
  std::vector<double> ms;
  for (int run = 0; run < kReferenceRuns; ++run) {
    const auto start = Clock::now();
    checker.check(scene.configurations.spheres, results);
    ms.push_back(microseconds(Clock::now() - start) / 1e3);
  }
  std::size_t colliding = 0;
  for (const ConfigurationResult& r : results) colliding += r.free ? 0 : 1;
  // From joint values: the test robot's files again (the URDF and its meshes, the spheres as
  // cuRobo's YAML), the values in the model's order as float64 and the base's pose.
  const test::TestRobot robot = test::write_test_robot(dir / "robot", test::standard_test_robot());
  tools::write_robot_spheres(dir / "arm.yml", tools::SphereFileFormat::Curobo, scene.arm.robot,
                             scene.arm.links);
  const RobotModel model = arm_model(scene.arm);
  const std::vector<double> values = in_model_order(scene.arm, model, scene.configurations.values);
  write("values.f64", values.data(), values.size() * sizeof(double));
  const Transform& base = scene.arm.base;
  const std::vector<float> base_pose = {
      base.translation.x(), base.translation.y(), base.translation.z(), base.rotation.x(),
      base.rotation.y(),    base.rotation.z(),    base.rotation.w()};
  write("base.f32", base_pose.data(), base_pose.size() * sizeof(float));
  const RobotChecker robot_checker(*scene.query, model);
  std::vector<ConfigurationResult> from_values(results.size());
  std::vector<double> values_ms;
  for (int run = 0; run < kReferenceRuns; ++run) {
    const auto start = Clock::now();
    robot_checker.check(values, from_values);
    values_ms.push_back(microseconds(Clock::now() - start) / 1e3);
  }
  std::size_t values_colliding = 0;
  for (const ConfigurationResult& r : from_values) values_colliding += r.free ? 0 : 1;
  std::printf(
      "configurations %zu spheres %zu colliding %zu cpp_loop_ms %.3f urdf %s package %s "
      "values_colliding %zu cpp_values_ms %.3f\n",
      results.size(), scene.arm.spheres(), colliding, median(ms), robot.urdf.string().c_str(),
      robot.package_option.c_str(), values_colliding, median(values_ms));
}

}  // namespace
}  // namespace sphys::query_bench

int main(int argc, char** argv) {
  sphys::query_bench::Options options;
  CLI::App app("sphys-query-bench: sphys's queries beside Bullet and FCL (docs/queries.md)");
  app.add_option("--ray-stacks", options.ray_stacks, "Stacks of 10 bunnies for the rays");
  app.add_option("--check-stacks", options.check_stacks,
                 "Stacks of 10 bunnies that --write-check-pile settles");
  app.add_option("--rays", options.rays, "Rays cast");
  app.add_option("--configurations", options.configurations, "Robot configurations checked");
  app.add_option("--fcl-configurations", options.fcl_configurations, "Of them, checked by FCL too");
  app.add_option("--distance-pairs", options.distance_pairs, "Bunny pairs measured");
  app.add_option("--spheres", options.spheres, "The robot's spheres (spherize --spheres)");
  std::vector<std::string> sections = {"rays", "checks", "distance"};
  app.add_option("--sections", sections, "Which of rays, checks, distance to run");
  app.add_option("--check-pile", options.check_pile,
                 "The checks' pile, a scene of bunnies at rest (default: the one kept with the "
                 "sources)");
  std::string write_pile;
  app.add_option("--write-check-pile", write_pile,
                 "Instead: settle --check-stacks stacks of 10 bunnies and write them to this scene "
                 "file, for --check-pile");
  std::string python_dir;
  app.add_option("--python-reference", python_dir,
                 "Instead: write the checks' world and configurations to this folder and time "
                 "the C++ loop over them (bench/query_python_bench.py)");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!write_pile.empty()) {
      sphys::examples::write_bunny_pile(
          sphys::examples::settle_bunny_pile(options.check_stacks, 10, 900), write_pile);
      return 0;
    }
    if (!python_dir.empty()) {
      sphys::query_bench::python_reference(options, python_dir);
      return 0;
    }
    for (const std::string& section : sections) {
      if (section == "rays") {
        sphys::query_bench::rays(options);
      } else if (section == "checks") {
        sphys::query_bench::configuration_checks(options);
      } else if (section == "distance") {
        sphys::query_bench::distances(options);
      } else {
        throw sphys::Error("--sections: unknown section '" + section + "'");
      }
    }
  } catch (const sphys::Error& error) {
    std::fprintf(stderr, "sphys-query-bench: error: %s\n", error.what());
    return 2;
  }
  return 0;
}
