// A robot's checks from joint values: the float kinematics against robot_link_poses' double,
// every kernel against the others bit for bit, the checks against a loop over the posed spheres,
// motions against their states checked one by one, and bad input.

#include "sphys/robot_check.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/query_worlds.h"

namespace sphys::test {
namespace {

using testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

// A four-joint arm with every kind of joint: a base turning about y, a shoulder about z, a slide
// along the upper arm, a fixed elbow block and a continuous wrist, three spheres on each moving
// link; its base stands at (0.2, 0, -0.1) turned about y.
RobotModel test_arm() {
  RobotModel model;
  model.name = "test arm";
  const auto pose = [](double x, double y, double z, double angle, Eigen::Vector3d axis) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translate(Eigen::Vector3d(x, y, z));
    p.rotate(Eigen::AngleAxisd(angle, axis.normalized()));
    return p;
  };
  model.links = {{"base", -1, pose(0, 0.05, 0, 0, Eigen::Vector3d::UnitY()), -1},
                 {"turntable", 0, pose(0, 0.1, 0, 0.3, Eigen::Vector3d(1, 2, 0)), 0},
                 {"upper", 1, pose(0, 0.2, 0, 0, Eigen::Vector3d::UnitX()), 1},
                 {"slider", 2, pose(0.4, 0, 0, 0, Eigen::Vector3d::UnitX()), 2},
                 {"elbow", 3, pose(0.1, 0.05, 0, 0.7, Eigen::Vector3d(0, 1, 1)), -1},
                 {"wrist", 4, pose(0.2, 0, 0.02, -0.4, Eigen::Vector3d(1, 0, 1)), 3}};
  model.joints = {
      {"turn", RobotJointType::kRevolute, Eigen::Vector3d::UnitY(), -kPi, kPi},
      {"shoulder", RobotJointType::kRevolute, Eigen::Vector3d(0.6, 0, 0.8), -2.0, 2.5},
      {"slide", RobotJointType::kPrismatic, Eigen::Vector3d::UnitX(), -0.1, 0.3},
      {"wrist", RobotJointType::kContinuous, Eigen::Vector3d(0, 0, 1),
       -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}};
  for (std::int32_t link = 0; link < 6; ++link) {
    for (int k = 0; k < 3; ++k) {
      model.sphere_links.push_back(link);
      model.spheres.push_back({Vec3(0.1f * static_cast<float>(k), 0.03f * static_cast<float>(link),
                                    -0.02f * static_cast<float>(k)),
                               0.04f + 0.01f * static_cast<float>(k)});
    }
  }
  model.allowed_link_pairs = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}};
  model.base = pose(0.2, 0, -0.1, 0.5, Eigen::Vector3d::UnitY());
  return model;
}

// `count` configurations within the limits (the continuous wrist over several turns).
std::vector<double> random_values(QueryRng& rng, const RobotModel& model, std::size_t count) {
  std::vector<double> values;
  for (std::size_t n = 0; n < count; ++n) {
    for (const RobotModel::Joint& joint : model.joints) {
      const double low = std::isfinite(joint.lower) ? joint.lower : -20.0;
      const double high = std::isfinite(joint.upper) ? joint.upper : 20.0;
      values.push_back(std::uniform_real_distribution<double>(low, high)(rng));
    }
  }
  return values;
}

// A world of random bodies around the arm: some configurations collide, some do not.
World world_around_arm(QueryRng& rng) { return random_query_world(rng, 12, 0.9f); }

// Runs `make` with SPHYS_SIMD set to `lanes` (unset again after).
template <class Make>
auto with_lanes(const char* lanes, const Make& make) {
  setenv("SPHYS_SIMD", lanes, 1);
  auto made = make();
  unsetenv("SPHYS_SIMD");
  return made;
}

TEST(RobotCheck, FloatKinematicsAgreeWithTheDoubleReference) {
  QueryRng rng(1);
  const World world = world_around_arm(rng);
  const WorldQuery query(world);
  const RobotModel model = test_arm();
  const RobotChecker checker(query, model);
  const std::size_t count = 203;  // not a whole number of lanes
  const std::vector<double> values = random_values(rng, model, count);
  std::vector<float> spheres(count * model.spheres.size() * 4);
  checker.pose_spheres(values, spheres);
  double worst = 0.0;
  for (std::size_t n = 0; n < count; ++n) {
    const std::vector<Eigen::Isometry3d> poses =
        robot_link_poses(model, std::span(values).subspan(n * 4, 4));
    for (std::size_t s = 0; s < model.spheres.size(); ++s) {
      const Eigen::Vector3d expected = poses[static_cast<std::size_t>(model.sphere_links[s])] *
                                       model.spheres[s].center.cast<double>();
      const float* got = spheres.data() + (n * model.spheres.size() + s) * 4;
      worst = std::max(worst, (Eigen::Vector3d(got[0], got[1], got[2]) - expected).norm());
      EXPECT_EQ(got[3], model.spheres[s].radius);
    }
  }
  EXPECT_LT(worst, 1e-5) << "metres";
}

// A planar arm worked out by hand: `shoulder` turns about z at the base, the upper arm 1 m long
// along x; `elbow` turns about z at its end, a sphere 0.5 m out along the forearm. Its centre is
// the base's pose applied to (cos a + 0.5 cos(a + b), sin a + 0.5 sin(a + b), 0).
TEST(RobotCheck, ATwoLinkArmIsPosedWhereWorkedOutByHand) {
  RobotModel arm;
  arm.name = "planar";
  Eigen::Isometry3d elbow_origin = Eigen::Isometry3d::Identity();
  elbow_origin.translate(Eigen::Vector3d(1, 0, 0));
  arm.links = {{"base", -1, Eigen::Isometry3d::Identity(), -1},
               {"upper", 0, Eigen::Isometry3d::Identity(), 0},
               {"fore", 1, elbow_origin, 1}};
  arm.joints = {{"shoulder", RobotJointType::kRevolute, Eigen::Vector3d::UnitZ(), -kPi, kPi},
                {"elbow", RobotJointType::kRevolute, Eigen::Vector3d::UnitZ(), -kPi, kPi}};
  arm.sphere_links = {2};
  arm.spheres = {{Vec3(0.5f, 0.0f, 0.0f), 0.1f}};
  // The base 0.5 m along x and 0.25 m up, turned a quarter about z: (x, y, z) goes to
  // (0.5 - y, x, z + 0.25).
  arm.base = Eigen::Isometry3d::Identity();
  arm.base.translate(Eigen::Vector3d(0.5, 0, 0.25));
  arm.base.rotate(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  const World empty;
  const WorldQuery query(empty);
  const RobotChecker checker(query, arm);
  const std::vector<double> values = {0.0,      0.0,  kPi / 2, 0.0, kPi / 2,
                                      -kPi / 2, -0.7, 2.1,     3.0, -3.0};
  std::vector<float> spheres(values.size() / 2 * 4);
  checker.pose_spheres(values, spheres);
  for (std::size_t n = 0; n < values.size() / 2; ++n) {
    const double a = values[2 * n];
    const double b = values[2 * n + 1];
    const double x = std::cos(a) + 0.5 * std::cos(a + b);
    const double y = std::sin(a) + 0.5 * std::sin(a + b);
    const Eigen::Vector3d expected(0.5 - y, x, 0.25);
    // The double reference: the link poses, the sphere on its link.
    const std::vector<Eigen::Isometry3d> poses =
        robot_link_poses(arm, std::span(values).subspan(2 * n, 2));
    const Eigen::Vector3d reference = poses[2] * Eigen::Vector3d(0.5, 0, 0);
    EXPECT_LT((reference - expected).norm(), 1e-12) << n;
    EXPECT_LT((poses[1].translation() - Eigen::Vector3d(0.5, 0, 0.25)).norm(), 1e-12) << n;
    // The float kernel, within 1e-5 m.
    const float* got = spheres.data() + 4 * n;
    EXPECT_LT((Eigen::Vector3d(got[0], got[1], got[2]) - expected).norm(), 1e-5) << n;
    EXPECT_EQ(got[3], 0.1f);
  }
}

TEST(RobotCheck, EveryKernelGivesTheSameBits) {
  QueryRng rng(2);
  const World world = world_around_arm(rng);
  const WorldQuery query(world);
  const RobotModel model = test_arm();
  const std::vector<double> values = random_values(rng, model, 64);
  std::vector<std::vector<float>> posed;
  for (const char* lanes : {"portable", "sse2", "avx2"}) {
    std::optional<RobotChecker> checker;
    try {
      with_lanes(lanes, [&] {
        checker.emplace(query, model);
        return 0;
      });
    } catch (const Error&) {
      continue;  // lanes this processor lacks
    }
    EXPECT_STREQ(checker->lanes(), lanes);
    posed.emplace_back(values.size() / 4 * model.spheres.size() * 4);
    checker->pose_spheres(values, posed.back());
  }
  ASSERT_GE(posed.size(), 2u);
  for (std::size_t k = 1; k < posed.size(); ++k) {
    for (std::size_t i = 0; i < posed[0].size(); ++i) {
      ASSERT_EQ(std::bit_cast<std::uint32_t>(posed[0][i]),
                std::bit_cast<std::uint32_t>(posed[k][i]))
          << "kernel " << k << " float " << i;
    }
  }
}

// What a RobotChecker's answers are checked against: a ConfigurationChecker of the model's
// spheres, posed, with the same self-collision and allowed link pairs.
ConfigurationChecker checker_of_spheres(const WorldQuery& query, const RobotModel& model,
                                        bool self_collision) {
  ConfigurationCheckSettings settings;
  settings.self_collision = self_collision;
  settings.allowed_link_pairs = model.allowed_link_pairs;
  return ConfigurationChecker(query, model.sphere_links, settings);
}

TEST(RobotCheck, ChecksAsTheConfigurationCheckerDoesOnThePosedSpheres) {
  QueryRng rng(3);
  const World world = world_around_arm(rng);
  const WorldQuery query(world);
  const RobotModel model = test_arm();
  for (const bool self : {false, true}) {
    RobotCheckSettings settings;
    settings.self_collision = self;
    const RobotChecker checker(query, model, settings);
    const ConfigurationChecker spheres_checker = checker_of_spheres(query, model, self);
    const std::size_t count = 500;
    const std::vector<double> values = random_values(rng, model, count);
    std::vector<float> spheres(count * model.spheres.size() * 4);
    checker.pose_spheres(values, spheres);
    std::vector<ConfigurationResult> expected(count);
    spheres_checker.check(spheres, expected);
    const Parallel two(2);
    for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &two}) {
      std::vector<ConfigurationResult> got(count);
      checker.check(values, got, parallel);
      std::size_t colliding = 0;
      for (std::size_t n = 0; n < count; ++n) {
        EXPECT_EQ(got[n].free, expected[n].free) << n;
        EXPECT_EQ(got[n].sphere, expected[n].sphere) << n;
        EXPECT_EQ(got[n].body, expected[n].body) << n;
        EXPECT_EQ(got[n].other_sphere, expected[n].other_sphere) << n;
        colliding += got[n].free ? 0 : 1;
      }
      // Both answers occur, so the comparison means something.
      EXPECT_GT(colliding, count / 20);
      EXPECT_LT(colliding, count - count / 20);
    }
  }
}

// The states of a motion of `count` states from `from` to `to`, as check_motion makes them.
std::vector<double> motion_states(const RobotModel& model, std::span<const double> from,
                                  std::span<const double> to, std::uint32_t count) {
  const std::size_t joints = model.joints.size();
  std::vector<double> states(count * joints);
  for (std::uint32_t k = 0; k < count; ++k) {
    for (std::size_t j = 0; j < joints; ++j) {
      const double along = static_cast<double>(k) / (count - 1);
      states[k * joints + j] = k + 1 == count
                                   ? to[j]
                                   : std::clamp(from[j] + (to[j] - from[j]) * along,
                                                model.joints[j].lower, model.joints[j].upper);
    }
  }
  return states;
}

// Expects motion `m`'s answer to be that of its first colliding state in `each` (its states'
// answers, in order); whether it is free.
bool expect_as_its_states(const MotionResult& motion, std::span<const ConfigurationResult> each,
                          std::size_t m) {
  const auto first = std::ranges::find_if(each, [](const auto& r) { return !r.free; });
  if (first == each.end()) {
    EXPECT_TRUE(motion.free) << m;
    return true;
  }
  EXPECT_FALSE(motion.free) << m;
  EXPECT_EQ(motion.first_collision, first - each.begin()) << m;
  EXPECT_EQ(motion.collision.sphere, first->sphere) << m;
  EXPECT_EQ(motion.collision.body, first->body) << m;
  EXPECT_EQ(motion.collision.other_sphere, first->other_sphere) << m;
  return false;
}

// Motions from random configurations, `share` of the way to others, states `resolution` apart,
// with and without self-collision: each against every state posed and checked in order by the
// ConfigurationChecker. Some are free, some not.
void expect_motions_as_their_states(double share, double resolution) {
  QueryRng rng(5);
  const World world = world_around_arm(rng);
  const WorldQuery query(world);
  const RobotModel model = test_arm();
  const std::size_t joints = model.joints.size();
  const std::size_t per = model.spheres.size() * 4;
  for (const bool self : {false, true}) {
    RobotCheckSettings settings;
    settings.self_collision = self;
    const RobotChecker checker(query, model, settings);
    const ConfigurationChecker spheres_checker = checker_of_spheres(query, model, self);
    constexpr std::size_t kMotions = 200;
    const std::vector<double> ends = random_values(rng, model, 2 * kMotions);
    std::size_t free = 0;
    for (std::size_t m = 0; m < kMotions; ++m) {
      const std::span<const double> from = std::span(ends).subspan(2 * m * joints, joints);
      std::vector<double> to(joints);
      for (std::size_t j = 0; j < joints; ++j) {
        to[j] = from[j] + share * (ends[(2 * m + 1) * joints + j] - from[j]);
      }
      const MotionResult motion = checker.check_motion(from, to, resolution);
      std::vector<float> spheres(motion.states * per);
      checker.pose_spheres(motion_states(model, from, to, motion.states), spheres);
      std::vector<ConfigurationResult> each(motion.states);
      spheres_checker.check(spheres, each);
      free += expect_as_its_states(motion, each, m) ? 1 : 0;
    }
    // Both answers occur.
    EXPECT_GT(free, kMotions / 10);
    EXPECT_LT(free, kMotions - kMotions / 10);
  }
}

TEST(RobotCheck, MotionsFindTheFirstStateThatTheConfigurationCheckerFindsColliding) {
  // Short motions (a tenth of the way to another random configuration): some far from every
  // body.
  expect_motions_as_their_states(0.1, 0.01);
}

TEST(RobotCheck, LongerMotionsFindTheFirstStateThatTheConfigurationCheckerFindsColliding) {
  // A quarter of the way, tens to a couple of hundred states.
  expect_motions_as_their_states(0.25, 0.03);
}

// One link turning about y at the origin, a sphere of 0.1 m at x = 1 on it; a ball of 0.1 m at
// (0, 0, -1) in the world: the link's sphere meets it when the link has turned by pi/2 (x goes to
// -z), within the angle where the two spheres' centres are 0.2 m apart.
struct Sweep {
  World world;
  RobotModel model;
};

Sweep sweep() {
  Sweep s;
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), 0.1f}, -1}};
  BodyDesc ball;
  ball.tree = std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, 2));
  ball.is_static = true;
  ball.pose.translation = Vec3(0.0f, 0.0f, -1.0f);
  s.world.add_body(ball);
  s.model.name = "sweep";
  s.model.links = {{"base", -1, Eigen::Isometry3d::Identity(), -1},
                   {"arm", 0, Eigen::Isometry3d::Identity(), 0}};
  s.model.joints = {{"turn", RobotJointType::kRevolute, Eigen::Vector3d::UnitY(), -kPi, kPi}};
  s.model.sphere_links = {1};
  s.model.spheres = {{Vec3(1.0f, 0.0f, 0.0f), 0.1f}};
  return s;
}

TEST(RobotCheck, AMotionSweepingThroughABallCollidesWhereItsStatesDo) {
  const Sweep s = sweep();
  const WorldQuery query(s.world);
  const RobotChecker checker(query, s.model);
  // Touching at angle a when |(cos a, 0, -sin a) - (0, 0, -1)| <= 0.2, i.e. 2 - 2 sin a <= 0.04.
  const double touching = std::asin(1.0 - 0.02);
  const std::vector<double> from = {0.0};
  const std::vector<double> to = {kPi};
  const double resolution = 0.01;
  const MotionResult motion = checker.check_motion(from, to, resolution);
  EXPECT_FALSE(motion.free);
  EXPECT_EQ(motion.states, static_cast<std::uint32_t>(std::ceil(kPi / resolution)) + 1);
  // The states one by one, in order: the first colliding one is the motion's.
  std::int32_t first = -1;
  for (std::uint32_t k = 0; k < motion.states && first < 0; ++k) {
    const std::vector<double> value = {kPi * k / (motion.states - 1)};
    std::vector<ConfigurationResult> one(1);
    checker.check(value, one);
    if (!one[0].free) first = static_cast<std::int32_t>(k);
  }
  EXPECT_EQ(motion.first_collision, first);
  EXPECT_EQ(motion.collision.body, 0);
  EXPECT_DOUBLE_EQ(motion.last_free, static_cast<double>(first - 1) / (motion.states - 1));
  // The first colliding state's angle is within a step past the analytic first touch.
  EXPECT_NEAR(kPi * first / (motion.states - 1), touching, kPi / (motion.states - 1) + 1e-5);
  // The other way round, and a motion that stays clear.
  EXPECT_FALSE(checker.check_motion(to, from, resolution).free);
  const MotionResult clear = checker.check_motion(std::vector{0.0}, std::vector{1.0}, resolution);
  EXPECT_TRUE(clear.free);
  EXPECT_EQ(clear.first_collision, -1);
  EXPECT_EQ(clear.last_free, 1.0);
  // A start in the ball.
  const MotionResult inside =
      checker.check_motion(std::vector{kPi / 2}, std::vector{0.0}, resolution);
  EXPECT_EQ(inside.first_collision, 0);
  EXPECT_EQ(inside.last_free, 0.0);
  // A batch on two threads gives what one motion at a time gives.
  const Parallel two(2);
  const std::vector<double> starts = {0.0, kPi, 0.0, kPi / 2};
  const std::vector<double> ends = {kPi, 0.0, 1.0, 0.0};
  std::vector<MotionResult> batch(4);
  checker.check_motions(starts, ends, resolution, batch, &two);
  for (std::size_t m = 0; m < 4; ++m) {
    const MotionResult alone = checker.check_motion(std::span(starts).subspan(m, 1),
                                                    std::span(ends).subspan(m, 1), resolution);
    EXPECT_EQ(batch[m].first_collision, alone.first_collision) << m;
    EXPECT_EQ(batch[m].last_free, alone.last_free) << m;
  }
}

TEST(RobotCheck, MotionsCollideWhereOnlyStatesBetweenThoseSpreadAlongThemDo) {
  // The ball moved down and grown (centre 1.25 m below, radius 0.16 m): the sphere touches it
  // only within 0.064 rad of pi/2, where it dips below the box of states 0.14 rad or more
  // away. Long motions from below -2 rad to 0.5 rad or beyond, up to 210 states: the states
  // spread along a motion that are posed first (a kernel call's) are about 0.8 rad apart, so
  // that often none of them comes near the ball while some between them touch it.
  Sweep s = sweep();
  s.world = World();
  std::vector<SphereTreeNode> nodes{{{Vec3::Zero(), 0.16f}, -1}};
  BodyDesc ball;
  ball.tree = std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, 2));
  ball.is_static = true;
  ball.pose.translation = Vec3(0.0f, 0.0f, -1.25f);
  s.world.add_body(ball);
  const WorldQuery query(s.world);
  const RobotChecker checker(query, s.model);
  QueryRng rng(8);
  const double resolution = 0.03;
  std::size_t free = 0;
  for (std::size_t m = 0; m < 200; ++m) {
    std::vector<double> from = {std::uniform_real_distribution<double>(-kPi, -2.0)(rng)};
    std::vector<double> to = {std::uniform_real_distribution<double>(0.5, kPi)(rng)};
    if (m % 2 == 1) std::swap(from, to);
    const MotionResult motion = checker.check_motion(from, to, resolution);
    std::vector<ConfigurationResult> each(motion.states);
    checker.check(motion_states(s.model, from, to, motion.states), each);
    free += expect_as_its_states(motion, each, m) ? 1 : 0;
  }
  // Those ending before pi/2 are free; most others are not.
  EXPECT_GT(free, 40u);
  EXPECT_LT(free, 120u);
}

TEST(RobotCheck, BadJointValuesAreRefusedNamingTheJoint) {
  const Sweep s = sweep();
  const WorldQuery query(s.world);
  const RobotChecker checker(query, s.model);
  std::vector<ConfigurationResult> results(2);
  EXPECT_THAT(error_message([&] {
                checker.check(std::vector{0.0, 4.0}, results);
              }),
              AllOf(HasSubstr("configuration 1"), HasSubstr("'turn'"), HasSubstr("outside")));
  EXPECT_THAT(error_message([&] {
                checker.check(std::vector{std::numeric_limits<double>::quiet_NaN(), 0.0}, results);
              }),
              AllOf(HasSubstr("configuration 0"), HasSubstr("not finite")));
  EXPECT_THAT(error_message([&] { checker.check(std::vector{0.0}, results); }),
              HasSubstr("results"));
  // In a batch checked on threads, whichever thread meets which first: the first is named.
  std::vector<double> many(1000, 0.5);
  many[900] = std::numeric_limits<double>::infinity();
  many[700] = -3.5;
  many[701] = std::numeric_limits<double>::quiet_NaN();
  std::vector<ConfigurationResult> answers(many.size());
  const Parallel two(2);
  for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &two}) {
    EXPECT_THAT(error_message([&] { checker.check(many, answers, parallel); }),
                AllOf(HasSubstr("configuration 700,"), HasSubstr("outside")));
  }
  EXPECT_THAT(
      error_message([&] { (void)checker.check_motion(std::vector{0.0}, std::vector{-4.0}, 0.1); }),
      AllOf(HasSubstr("to:"), HasSubstr("'turn'"), HasSubstr("outside")));
  EXPECT_THAT(error_message([&] {
                (void)checker.check_motion(std::vector{std::numeric_limits<double>::quiet_NaN()},
                                           std::vector{0.0}, 0.1);
              }),
              AllOf(HasSubstr("from:"), HasSubstr("not finite")));
  EXPECT_THAT(
      error_message([&] { (void)checker.check_motion(std::vector{0.0}, std::vector{1.0}, 0.0); }),
      HasSubstr("resolution"));
  EXPECT_THAT(
      error_message([&] { (void)checker.check_motion(std::vector{0.0}, std::vector{1.0}, 1e-9); }),
      HasSubstr("states"));
}

TEST(RobotCheck, ABrokenModelIsRefusedNamingWhatIsWrong) {
  const Sweep s = sweep();
  const WorldQuery query(s.world);
  const auto refused = [&](const RobotModel& model) {
    return error_message([&] { RobotChecker checker(query, model); });
  };
  RobotModel model = s.model;
  model.links[1].parent = 1;
  EXPECT_THAT(refused(model), HasSubstr("parent must be listed before it"));
  model = s.model;
  model.joints[0].axis = Eigen::Vector3d(1, 1, 0);
  EXPECT_THAT(refused(model), HasSubstr("axis is not a unit vector"));
  model = s.model;
  model.joints[0].lower = 1.0;
  model.joints[0].upper = 0.0;
  EXPECT_THAT(refused(model), HasSubstr("lower <= upper"));
  model = s.model;
  model.spheres[0].radius = -1.0f;
  EXPECT_THAT(refused(model), HasSubstr("radius"));
  model = s.model;
  model.links[1].joint = -1;
  EXPECT_THAT(refused(model), HasSubstr("moves 0 links"));
  EXPECT_THAT(error_message([&] { (void)s.model.link_index("hand"); }), HasSubstr("'hand'"));
}

}  // namespace
}  // namespace sphys::test
