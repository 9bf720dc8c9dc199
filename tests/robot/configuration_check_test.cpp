// Batched configuration checks against a plain loop over every sphere and leaf sphere.

#include "sphys/configuration_check.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/query_worlds.h"

namespace sphys::test {
namespace {

bool touch(const float* a, const Sphere& b) {
  const double d = (Eigen::Vector3d(a[0], a[1], a[2]) - b.center.cast<double>()).norm();
  return d <= double(a[3]) + b.radius;
}

bool touch(const float* a, const float* b) {
  const double d = (Eigen::Vector3d(a[0], a[1], a[2]) - Eigen::Vector3d(b[0], b[1], b[2])).norm();
  return d <= double(a[3]) + b[3];
}

// The definition of ConfigurationResult, as loops.
ConfigurationResult oracle_check(const std::vector<WorldLeaf>& leaves, const float* spheres,
                                 const std::vector<std::int32_t>& links,
                                 const std::vector<std::array<std::int32_t, 2>>& allowed,
                                 bool self_collision) {
  ConfigurationResult result;
  for (std::size_t i = 0; i < links.size(); ++i) {
    for (const WorldLeaf& leaf : leaves) {
      if (touch(spheres + 4 * i, leaf.sphere)) {
        return {false, static_cast<std::int32_t>(i), static_cast<std::int32_t>(leaf.body.index),
                -1};
      }
    }
  }
  if (!self_collision) return result;
  for (std::size_t i = 0; i < links.size(); ++i) {
    for (std::size_t j = i + 1; j < links.size(); ++j) {
      const bool is_allowed = std::any_of(allowed.begin(), allowed.end(), [&](const auto& p) {
        return (p[0] == links[i] && p[1] == links[j]) || (p[1] == links[i] && p[0] == links[j]);
      });
      if (links[i] == links[j] || is_allowed) continue;
      if (touch(spheres + 4 * i, spheres + 4 * j)) {
        return {false, static_cast<std::int32_t>(i), -1, static_cast<std::int32_t>(j)};
      }
    }
  }
  return result;
}

// A chain of `links` links of a few spheres each, placed at random in the world per
// configuration: some free, some not.
std::vector<float> random_configurations(QueryRng& rng, std::size_t count,
                                         const std::vector<std::int32_t>& links, float half_side) {
  std::vector<float> out;
  for (std::size_t c = 0; c < count; ++c) {
    const Vec3 base = uniform_point(rng, half_side);
    for (std::size_t i = 0; i < links.size(); ++i) {
      const Vec3 centre =
          base + uniform_point(rng, 0.4f) + Vec3(0, 0.1f * static_cast<float>(links[i]), 0);
      out.insert(out.end(), {centre.x(), centre.y(), centre.z(), uniform_in(rng, 0.01f, 0.08f)});
    }
  }
  return out;
}

TEST(ConfigurationCheck, AnswersMatchEverySpherePairOnAnyThreads) {
  QueryRng rng(41);
  const World world = random_query_world(rng, 40, 2.5f);
  const WorldQuery query(world);
  const std::vector<std::int32_t> links{0, 0, 1, 1, 1, 2, 3, 3, 4, 4, 4, 4};
  const std::vector<std::array<std::int32_t, 2>> allowed{{0, 1}, {1, 2}, {3, 2}};
  const std::vector<WorldLeaf> leaves = oracle_leaves(world);
  constexpr std::size_t kConfigurations = 3000;
  const std::vector<float> spheres = random_configurations(rng, kConfigurations, links, 3.0f);
  const Parallel two(2);
  for (const bool self_collision : {false, true}) {
    ConfigurationCheckSettings settings;
    settings.self_collision = self_collision;
    settings.allowed_link_pairs = allowed;
    const ConfigurationChecker checker(query, links, settings);
    EXPECT_EQ(checker.links(), 5u);
    for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &two}) {
      std::vector<ConfigurationResult> results(kConfigurations);
      checker.check(spheres, results, parallel);
      std::size_t free = 0;
      std::size_t self_hits = 0;
      for (std::size_t c = 0; c < kConfigurations; ++c) {
        const ConfigurationResult expected = oracle_check(
            leaves, spheres.data() + c * 4 * links.size(), links, allowed, self_collision);
        ASSERT_EQ(results[c].free, expected.free) << "configuration " << c;
        EXPECT_EQ(results[c].sphere, expected.sphere);
        EXPECT_EQ(results[c].other_sphere, expected.other_sphere);
        free += results[c].free ? 1 : 0;
        self_hits += results[c].other_sphere >= 0 ? 1 : 0;
        // The body named is one the sphere touches (any of them may be named).
        if (results[c].body >= 0) {
          const float* sphere = spheres.data() + c * 4 * links.size() + 4 * results[c].sphere;
          EXPECT_TRUE(std::any_of(leaves.begin(), leaves.end(), [&](const WorldLeaf& leaf) {
            return leaf.body.index == std::uint32_t(results[c].body) && touch(sphere, leaf.sphere);
          }));
        }
      }
      // Both answers occur often enough to be tested.
      EXPECT_GT(free, kConfigurations / 10);
      EXPECT_LT(free, kConfigurations * 9 / 10);
      if (self_collision) {
        EXPECT_GT(self_hits, 10u);
      }
    }
  }
}

TEST(ConfigurationCheck, AReachBallGivesTheSameAnswersInsideItAndOutside) {
  // Configurations spread over a cube of half side 3 m; the reach ball of 2 m about the origin
  // holds some of them whole (its groups scanned) and not others (walked).
  QueryRng rng(67);
  const World world = random_query_world(rng, 40, 2.5f);
  const WorldQuery query(world);
  const std::vector<std::int32_t> links{0, 0, 1, 1, 1, 2, 3, 3};
  const std::vector<WorldLeaf> leaves = oracle_leaves(world);
  constexpr std::size_t kConfigurations = 3000;
  const std::vector<float> spheres = random_configurations(rng, kConfigurations, links, 3.0f);
  ConfigurationCheckSettings settings;
  settings.reach = Sphere{Vec3::Zero(), 2.0f};
  const ConfigurationChecker checker(query, links, settings);
  std::vector<ConfigurationResult> results(kConfigurations);
  checker.check(spheres, results);
  std::size_t inside = 0;
  for (std::size_t c = 0; c < kConfigurations; ++c) {
    const float* configuration = spheres.data() + c * 4 * links.size();
    const ConfigurationResult expected = oracle_check(leaves, configuration, links, {}, false);
    ASSERT_EQ(results[c].free, expected.free) << "configuration " << c;
    EXPECT_EQ(results[c].sphere, expected.sphere);
    bool whole = true;
    for (std::size_t i = 0; i < links.size(); ++i) {
      const float* s = configuration + 4 * i;
      for (int axis = 0; axis < 3; ++axis) whole = whole && std::abs(s[axis]) + s[3] < 2.0f;
    }
    inside += whole ? 1 : 0;
  }
  // Both ways are taken often.
  EXPECT_GT(inside, kConfigurations / 10);
  EXPECT_LT(inside, kConfigurations * 9 / 10);
  ConfigurationCheckSettings bad;
  bad.reach = Sphere{Vec3::Zero(), -1.0f};
  EXPECT_THAT(error_message([&] { ConfigurationChecker(query, links, bad); }),
              testing::HasSubstr("reach"));
}

TEST(ConfigurationCheck, GatheredConfigurationsGetTheAnswersOfEverySpherePair) {
  // Configurations gathered in runs of 1 to 40, as a motion's states are (each run's links bounded
  // together, from near to spread over the world), against the oracle; a NaN sphere in one run.
  QueryRng rng(43);
  const World world = random_query_world(rng, 40, 2.5f);
  const WorldQuery query(world);
  const std::vector<std::int32_t> links{0, 0, 1, 1, 1, 2, 3, 3, 4, 4, 4, 4};
  const std::vector<std::array<std::int32_t, 2>> allowed{{0, 1}, {1, 2}, {3, 2}};
  const std::vector<WorldLeaf> leaves = oracle_leaves(world);
  const std::size_t per = 4 * links.size();
  for (const bool self_collision : {false, true}) {
    ConfigurationCheckSettings settings;
    settings.self_collision = self_collision;
    settings.allowed_link_pairs = allowed;
    const ConfigurationChecker checker(query, links, settings);
    ConfigurationChecker::Run run(checker);
    std::size_t free = 0;
    std::size_t checked = 0;
    for (std::size_t count : {1u, 2u, 8u, 40u, 40u, 17u}) {
      // A run's configurations near each other: one random configuration, moved a little.
      const std::vector<float> first = random_configurations(rng, 1, links, 3.0f);
      std::vector<float> spheres;
      for (std::size_t c = 0; c < count; ++c) {
        const Vec3 shift = uniform_point(rng, 0.05f * static_cast<float>(count));
        for (std::size_t i = 0; i < links.size(); ++i) {
          spheres.insert(spheres.end(), {first[4 * i] + shift.x(), first[4 * i + 1] + shift.y(),
                                         first[4 * i + 2] + shift.z(), first[4 * i + 3]});
        }
      }
      if (count == 17) spheres[per * 5 + 4 * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
      run.gather(spheres.data(), count);
      // In an order of their own, as a motion's coarse-to-fine order is.
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t c = (k * 7) % count;
        const ConfigurationResult got = run.check_gathered(c);
        ConfigurationResult expected =
            oracle_check(leaves, spheres.data() + c * per, links, allowed, self_collision);
        // The NaN sphere collides, unless a sphere before it touches a body.
        if (count == 17 && c == 5 && !(expected.body >= 0 && expected.sphere < 3)) {
          expected = {false, 3, -1, -1};
        }
        ASSERT_EQ(got.free, expected.free) << count << " " << c;
        EXPECT_EQ(got.sphere, expected.sphere);
        EXPECT_EQ(got.other_sphere, expected.other_sphere);
        free += got.free ? 1 : 0;
        ++checked;
      }
    }
    EXPECT_GT(free, 0u);
    EXPECT_LT(free, checked);
    EXPECT_THAT(error_message([&] { (void)run.check_gathered(17); }),
                testing::HasSubstr("17 gathered"));
  }
}

TEST(ConfigurationCheck, ALinkSpanningTheWorldIsCheckedSphereBySphere) {
  // Two spheres of one link at opposite corners: the link's bound holds every group of the
  // world, more than a link keeps as candidates, so its spheres walk the hierarchy themselves.
  QueryRng rng(59);
  const World world = random_query_world(rng, 60, 2.0f);
  const WorldQuery query(world);
  const std::vector<WorldLeaf> leaves = oracle_leaves(world);
  const std::vector<std::int32_t> links{0, 0, 0};
  const ConfigurationChecker checker(query, links);
  constexpr std::size_t kConfigurations = 500;
  std::vector<float> spheres;
  for (std::size_t c = 0; c < kConfigurations; ++c) {
    const Vec3 middle = uniform_point(rng, 2.0f);
    for (const Vec3& centre : {Vec3(-3, -3, -3), middle, Vec3(3, 3, 3)}) {
      spheres.insert(spheres.end(), {centre.x(), centre.y(), centre.z(), 0.3f});
    }
  }
  std::vector<ConfigurationResult> results(kConfigurations);
  checker.check(spheres, results);
  std::size_t free = 0;
  for (std::size_t c = 0; c < kConfigurations; ++c) {
    const ConfigurationResult expected =
        oracle_check(leaves, spheres.data() + c * 12, links, {}, false);
    ASSERT_EQ(results[c].free, expected.free) << "configuration " << c;
    EXPECT_EQ(results[c].sphere, expected.sphere);
    free += results[c].free ? 1 : 0;
  }
  EXPECT_GT(free, kConfigurations / 10);
  EXPECT_LT(free, kConfigurations * 9 / 10);
}

TEST(ConfigurationCheck, LinkPosesGiveTheSameAnswersAsPosedSpheres) {
  QueryRng rng(43);
  const World world = random_query_world(rng, 30, 2.0f);
  const WorldQuery query(world);
  const std::vector<std::int32_t> links{0, 0, 1, 2, 2, 2};
  std::vector<Sphere> local;
  for (std::size_t i = 0; i < links.size(); ++i) {
    local.push_back({uniform_point(rng, 0.3f), uniform_in(rng, 0.02f, 0.1f)});
  }
  constexpr std::size_t kConfigurations = 500;
  std::vector<Transform> poses;
  std::vector<float> posed;
  for (std::size_t c = 0; c < kConfigurations; ++c) {
    for (int l = 0; l < 3; ++l) {
      Transform pose;
      pose.rotation = uniform_rotation(rng);
      pose.translation = uniform_point(rng, 2.5f);
      poses.push_back(pose);
    }
    for (std::size_t i = 0; i < links.size(); ++i) {
      const Transform& pose = poses[c * 3 + links[i]];
      const Vec3 centre = pose.rotation.toRotationMatrix() * local[i].center + pose.translation;
      posed.insert(posed.end(), {centre.x(), centre.y(), centre.z(), local[i].radius});
    }
  }
  ConfigurationCheckSettings settings;
  settings.self_collision = true;
  const ConfigurationChecker checker(query, links, settings);
  std::vector<ConfigurationResult> from_poses(kConfigurations);
  std::vector<ConfigurationResult> from_spheres(kConfigurations);
  checker.check_link_poses(poses, local, from_poses);
  checker.check(posed, from_spheres);
  for (std::size_t c = 0; c < kConfigurations; ++c) {
    EXPECT_EQ(from_poses[c].free, from_spheres[c].free);
    EXPECT_EQ(from_poses[c].sphere, from_spheres[c].sphere);
  }
}

TEST(ConfigurationCheck, TheFilterLeavesBodiesOutAndNaNSpheresNeverPassAsFree) {
  QueryRng rng(47);
  const World world = random_query_world(rng, 10, 1.0f);
  const WorldQuery query(world);
  // One sphere over everything: it touches every body.
  const std::vector<float> everywhere{0, 0, 0, 10};
  ConfigurationCheckSettings none;
  none.filter.mask = 0;
  std::vector<ConfigurationResult> result(1);
  ConfigurationChecker(query, {0}, none).check(everywhere, result);
  EXPECT_TRUE(result[0].free);
  ConfigurationChecker(query, {0}).check(everywhere, result);
  EXPECT_FALSE(result[0].free);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> far_and_nan{100, 100, 100, 0.1f, nan, 100, 100, 0.1f};
  ConfigurationChecker(query, {0, 1}).check(far_and_nan, result);
  EXPECT_FALSE(result[0].free);
  EXPECT_EQ(result[0].sphere, 1);
}

// Bodies whose trees have 4 levels (children sticking out of their parents, some nodes without
// children), in a world that uses 2 of them.
World deep_tree_world(QueryRng& rng, int bodies, float half_side) {
  WorldSettings settings;
  settings.gravity = Vec3::Zero();
  settings.collision.tree_depth = 2;
  World world(settings);
  for (int i = 0; i < bodies; ++i) {
    BodyDesc desc;
    desc.tree = random_query_tree(rng, std::uniform_int_distribution<int>(2, 8)(rng), 4);
    desc.pose.rotation = uniform_rotation(rng);
    desc.pose.translation = uniform_point(rng, half_side);
    desc.is_static = true;
    world.add_body(desc);
  }
  return world;
}

// The first sphere that touches, at `depth` levels, a body it also touches at the world's: its
// index and the bodies it could name (-1 and none when free).
std::pair<std::int32_t, std::vector<std::uint32_t>> first_touching_at(
    const std::vector<WorldLeaf>& world_leaves, const std::vector<WorldLeaf>& deep_leaves,
    const float* spheres, std::size_t count) {
  const auto touched = [&](const std::vector<WorldLeaf>& leaves, const float* sphere) {
    std::vector<std::uint32_t> bodies;
    for (const WorldLeaf& leaf : leaves) {
      if (touch(sphere, leaf.sphere)) bodies.push_back(leaf.body.index);
    }
    return bodies;
  };
  for (std::size_t i = 0; i < count; ++i) {
    const std::vector<std::uint32_t> coarse = touched(world_leaves, spheres + 4 * i);
    std::vector<std::uint32_t> both;
    for (const std::uint32_t body : touched(deep_leaves, spheres + 4 * i)) {
      if (std::ranges::find(coarse, body) != coarse.end()) both.push_back(body);
    }
    if (!both.empty()) return {static_cast<std::int32_t>(i), both};
  }
  return {-1, {}};
}

TEST(ConfigurationCheck, ADeeperLevelCollidesWhereASphereTouchesABodyAtBothLevels) {
  QueryRng rng(59);
  const World world = deep_tree_world(rng, 30, 2.5f);
  const WorldQuery query(world);
  const std::vector<std::int32_t> links{0, 0, 1, 1, 1, 2};
  const std::vector<WorldLeaf> world_leaves = oracle_leaves(world);
  constexpr std::size_t kConfigurations = 3000;
  const std::vector<float> spheres = random_configurations(rng, kConfigurations, links, 3.0f);
  std::vector<ConfigurationResult> at_world(kConfigurations);
  ConfigurationChecker(query, links).check(spheres, at_world);
  for (const int depth : {2, 3, 4}) {
    SCOPED_TRACE(depth);
    ConfigurationCheckSettings settings;
    settings.tree_depth = depth;
    const ConfigurationChecker checker(query, links, settings);
    const std::vector<WorldLeaf> deep_leaves = oracle_leaves(world, {}, depth);
    std::vector<ConfigurationResult> results(kConfigurations);
    checker.check(spheres, results);
    std::size_t freed = 0;
    for (std::size_t c = 0; c < kConfigurations; ++c) {
      const auto [sphere, bodies] = first_touching_at(
          world_leaves, deep_leaves, spheres.data() + c * 4 * links.size(), links.size());
      ASSERT_EQ(results[c].free, sphere < 0) << "configuration " << c;
      EXPECT_EQ(results[c].sphere, sphere);
      if (sphere >= 0) {
        EXPECT_THAT(bodies, testing::Contains(std::uint32_t(results[c].body)));
      }
      // Never one more collision than at the world's level.
      if (at_world[c].free) {
        EXPECT_TRUE(results[c].free);
      }
      freed += results[c].free && !at_world[c].free ? 1 : 0;
    }
    // Deeper levels free configurations that the world's leaves alone call colliding.
    if (depth > 2) {
      EXPECT_GT(freed, kConfigurations / 100);
    } else {
      EXPECT_EQ(freed, 0u);
    }
  }
}

TEST(ConfigurationCheck, ALevelAboveTheWorldsIsAnError) {
  QueryRng rng(61);
  const World world = deep_tree_world(rng, 3, 1.0f);
  const WorldQuery query(world);
  using testing::HasSubstr;
  for (const int depth : {-1, 1, 17}) {
    ConfigurationCheckSettings settings;
    settings.tree_depth = depth;
    EXPECT_THAT(error_message([&] { ConfigurationChecker(query, {0}, settings); }),
                HasSubstr("tree_depth: " + std::to_string(depth) + " levels"));
  }
  // A world that uses every level has none deeper.
  const World every_level = random_query_world(rng, 3, 1.0f);
  const WorldQuery every_query(every_level);
  ConfigurationCheckSettings three;
  three.tree_depth = 3;
  EXPECT_THAT(error_message([&] { ConfigurationChecker(every_query, {0}, three); }),
              HasSubstr("shallower than the world's (every level)"));
}

TEST(ConfigurationCheck, BadShapesAreErrorsNamingTheArgument) {
  QueryRng rng(53);
  const World world = random_query_world(rng, 3, 1.0f);
  const WorldQuery query(world);
  using testing::HasSubstr;
  EXPECT_THAT(error_message([&] { ConfigurationChecker(query, {}); }), HasSubstr("sphere_links"));
  EXPECT_THAT(error_message([&] {
                ConfigurationChecker(query, {0, -1});
              }),
              HasSubstr("sphere_links[1]"));
  ConfigurationCheckSettings bad_pair;
  bad_pair.self_collision = true;
  bad_pair.allowed_link_pairs = {{0, 5}};
  EXPECT_THAT(error_message([&] {
                ConfigurationChecker(query, {0, 1}, bad_pair);
              }),
              HasSubstr("allowed_link_pairs"));
  const ConfigurationChecker checker(query, {0, 1});
  std::vector<ConfigurationResult> results(2);
  EXPECT_THAT(error_message([&] { checker.check(std::vector<float>(7), results); }),
              HasSubstr("spheres: 7 floats"));
  EXPECT_THAT(error_message([&] { checker.check(std::vector<float>(8), results); }),
              HasSubstr("results: 2 entries for 1"));
  EXPECT_THAT(error_message([&] {
                checker.check_link_poses(std::vector<Transform>(3), std::vector<Sphere>(2),
                                         results);
              }),
              HasSubstr("link_poses"));
}

}  // namespace
}  // namespace sphys::test
