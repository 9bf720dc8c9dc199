// Every query against a plain loop over all leaf spheres (support/query_worlds.h), on random
// worlds: ray hits and distances to 1e-5 m, the same bodies.

#include "sphys/world_query.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/query_worlds.h"

namespace sphys::test {
namespace {

constexpr double kTolerance = 1e-5;  // unit: m

// Where a unit ray enters a sphere, in double; none for a miss, 0 from inside.
std::optional<double> oracle_entry(const Vec3& origin, const Vec3& unit, const Sphere& sphere) {
  const Eigen::Vector3d o = origin.cast<double>();
  const Eigen::Vector3d d = unit.cast<double>().normalized();
  const Eigen::Vector3d m = o - sphere.center.cast<double>();
  const double r = sphere.radius;
  if (m.squaredNorm() <= r * r) return 0.0;
  const double b = m.dot(d);
  const double disc = b * b - (m.squaredNorm() - r * r);
  if (b >= 0.0 || disc < 0.0) return std::nullopt;
  return -b - std::sqrt(disc);
}

struct OracleHit {
  BodyId body;
  double distance = 0.0;
};

// Per body its nearest entry within max_distance, nearest first.
std::vector<OracleHit> oracle_ray(const World& world, const Ray& ray, const QueryFilter& filter) {
  std::vector<OracleHit> hits;
  for (const WorldLeaf& leaf : oracle_leaves(world, filter)) {
    const std::optional<double> t = oracle_entry(ray.origin, ray.direction, leaf.sphere);
    if (!t || *t > ray.max_distance) continue;
    const auto same = std::find_if(hits.begin(), hits.end(),
                                   [&](const OracleHit& h) { return h.body == leaf.body; });
    if (same == hits.end()) {
      hits.push_back({leaf.body, *t});
    } else {
      same->distance = std::min(same->distance, *t);
    }
  }
  std::sort(hits.begin(), hits.end(),
            [](const OracleHit& a, const OracleHit& b) { return a.distance < b.distance; });
  return hits;
}

Ray random_ray(QueryRng& rng, float half_side) {
  Ray ray;
  ray.origin = uniform_point(rng, half_side * 1.5f);
  // Aimed near the middle, so that most rays cross the pile.
  ray.direction = uniform_point(rng, half_side * 0.5f) - ray.origin;
  if (rng() % 4 == 0) ray.max_distance = uniform_in(rng, 0.5f, 4.0f);
  return ray;
}

TEST(WorldQuery, NearestRayHitMatchesEveryLeafSphere) {
  for (const int tree_depth : {0, 2}) {
    QueryRng rng(11 + tree_depth);
    const World world = random_query_world(rng, 60, 2.0f, tree_depth);
    const WorldQuery query(world);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
      const Ray ray = random_ray(rng, 2.0f);
      const std::vector<OracleHit> expected = oracle_ray(world, ray, {});
      const std::optional<RayHit> hit = query.cast_ray(ray);
      ASSERT_EQ(hit.has_value(), !expected.empty()) << "ray " << i;
      if (!hit) continue;
      ++hits;
      EXPECT_NEAR(hit->distance, expected.front().distance, kTolerance) << "ray " << i;
      // Another body is right only where it is as near (a tie within rounding).
      if (!(hit->body == expected.front().body)) {
        const auto same = std::find_if(expected.begin(), expected.end(),
                                       [&](const OracleHit& h) { return h.body == hit->body; });
        ASSERT_NE(same, expected.end());
        EXPECT_NEAR(same->distance, expected.front().distance, kTolerance);
      }
      // The point lies on the leaf sphere's surface (or is the origin, from inside) and the
      // normal is the sphere's outward one there.
      const Sphere leaf = world.tree(hit->body).sphere(hit->leaf);
      const Transform pose = world.bodies().poses()[hit->body.index];
      const Vec3 centre = pose.rotation.toRotationMatrix() * leaf.center + pose.translation;
      if (hit->distance > 0.0f) {
        EXPECT_NEAR((hit->point - centre).norm(), leaf.radius, kTolerance);
        EXPECT_LT((hit->normal - (hit->point - centre).normalized()).norm(), 1e-4f);
      }
      EXPECT_NEAR((hit->point - ray.origin).norm(), hit->distance, kTolerance);
    }
    EXPECT_GT(hits, 500) << "too few rays hit to test anything";
  }
}

TEST(WorldQuery, AllRayHitsAreEveryBodyOnTheRay) {
  QueryRng rng(5);
  const World world = random_query_world(rng, 80, 1.5f);
  const WorldQuery query(world);
  std::size_t bodies_hit = 0;
  std::size_t rays_through_several = 0;
  for (int i = 0; i < 1000; ++i) {
    const Ray ray = random_ray(rng, 2.0f);
    const std::vector<OracleHit> expected = oracle_ray(world, ray, {});
    const std::vector<RayHit> hits = query.cast_ray_all(ray);
    ASSERT_EQ(hits.size(), expected.size()) << "ray " << i;
    bodies_hit += hits.size();
    rays_through_several += hits.size() > 1 ? 1 : 0;
    for (std::size_t k = 0; k < hits.size(); ++k) {
      if (k > 0) {
        EXPECT_LE(hits[k - 1].distance, hits[k].distance);
      }
      const auto same = std::find_if(expected.begin(), expected.end(),
                                     [&](const OracleHit& h) { return h.body == hits[k].body; });
      ASSERT_NE(same, expected.end()) << "ray " << i;
      EXPECT_NEAR(hits[k].distance, same->distance, kTolerance);
    }
  }
  EXPECT_GT(bodies_hit, 700u);
  EXPECT_GT(rays_through_several, 150u);
}

TEST(WorldQuery, ManyRaysAnswerAsOneAtATimeOnAnyThreads) {
  QueryRng rng(7);
  const World world = random_query_world(rng, 40, 2.0f);
  const WorldQuery query(world);
  std::vector<Ray> rays;
  for (int i = 0; i < 500; ++i) rays.push_back(random_ray(rng, 2.0f));
  const Parallel two(2);
  for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &two}) {
    std::vector<std::optional<RayHit>> hits(rays.size());
    query.cast_rays(rays, {}, hits, parallel);
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const std::optional<RayHit> one = query.cast_ray(rays[i]);
      ASSERT_EQ(hits[i].has_value(), one.has_value());
      if (one) {
        EXPECT_EQ(hits[i]->body, one->body);
        EXPECT_EQ(hits[i]->distance, one->distance);
      }
    }
  }
}

std::set<std::uint32_t> slots(const std::vector<BodyId>& ids) {
  std::set<std::uint32_t> out;
  for (const BodyId id : ids) out.insert(id.index);
  return out;
}

template <class Touches>
std::set<std::uint32_t> oracle_overlap(const World& world, const QueryFilter& filter,
                                       const Touches& touches) {
  std::set<std::uint32_t> out;
  for (const WorldLeaf& leaf : oracle_leaves(world, filter)) {
    if (touches(leaf.sphere)) out.insert(leaf.body.index);
  }
  return out;
}

double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& low,
                    const Eigen::Vector3d& high) {
  return (p.cwiseMax(low).cwiseMin(high) - p).norm();
}

TEST(WorldQuery, OverlapsAreTheBodiesOfTouchingLeafSpheres) {
  QueryRng rng(13);
  const World world = random_query_world(rng, 60, 2.0f);
  const WorldQuery query(world);
  std::size_t found = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec3 centre = uniform_point(rng, 2.0f);
    const float radius = uniform_in(rng, 0.0f, 0.6f);
    const auto sphere_expected = oracle_overlap(world, {}, [&](const Sphere& s) {
      return (s.center.cast<double>() - centre.cast<double>()).norm() <= double(s.radius) + radius;
    });
    EXPECT_EQ(slots(query.overlap_sphere(centre, radius)), sphere_expected);
    found += sphere_expected.size();

    const Aabb box{centre - uniform_point(rng, 0.4f).cwiseAbs(),
                   centre + uniform_point(rng, 0.4f).cwiseAbs()};
    EXPECT_EQ(slots(query.overlap_aabb(box)), oracle_overlap(world, {}, [&](const Sphere& s) {
                return box_distance(s.center.cast<double>(), box.min.cast<double>(),
                                    box.max.cast<double>()) <= s.radius;
              }));

    OrientedBox turned;
    turned.pose.rotation = uniform_rotation(rng);
    turned.pose.translation = centre;
    turned.half_extents = uniform_point(rng, 0.5f).cwiseAbs();
    const Eigen::Matrix3d rotation = turned.pose.rotation.toRotationMatrix().cast<double>();
    EXPECT_EQ(slots(query.overlap_box(turned)), oracle_overlap(world, {}, [&](const Sphere& s) {
                const Eigen::Vector3d local =
                    rotation.transpose() *
                    (s.center.cast<double>() - turned.pose.translation.cast<double>());
                const Eigen::Vector3d half = turned.half_extents.cast<double>();
                return box_distance(local, -half, half) <= s.radius;
              }));
  }
  EXPECT_GT(found, 100u);
}

TEST(WorldQuery, TreeAndBodyOverlapsMatchEveryLeafPair) {
  QueryRng rng(17);
  const World world = random_query_world(rng, 50, 2.0f);
  const WorldQuery query(world);
  for (int i = 0; i < 200; ++i) {
    const BodyId body =
        world.id_of(std::uniform_int_distribution<std::uint32_t>(0, world.body_slots() - 1)(rng));
    Transform pose;
    pose.rotation = uniform_rotation(rng);
    pose.translation = uniform_point(rng, 2.0f);
    const SphereTree& tree = world.tree(body);
    std::vector<Sphere> probe;
    for (const std::uint32_t node : tree.leaves()) {
      probe.push_back(
          {pose.rotation.toRotationMatrix() * tree.sphere(node).center + pose.translation,
           tree.sphere(node).radius});
    }
    QueryFilter others;
    others.skip = {body};
    const auto expected = oracle_overlap(world, others, [&](const Sphere& s) {
      return std::any_of(probe.begin(), probe.end(), [&](const Sphere& p) {
        return (p.center.cast<double>() - s.center.cast<double>()).norm() <=
               double(p.radius) + s.radius;
      });
    });
    EXPECT_EQ(slots(query.overlap_body(body, pose)), expected);
    EXPECT_EQ(slots(query.overlap_tree(tree, pose, others)), expected);
  }
}

// The smallest gap over every leaf pair, in double.
double oracle_distance(const std::vector<Sphere>& a, const std::vector<Sphere>& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const Sphere& x : a) {
    for (const Sphere& y : b) {
      best = std::min(
          best, (x.center.cast<double>() - y.center.cast<double>()).norm() - x.radius - y.radius);
    }
  }
  return best;
}

std::vector<Sphere> leaves_of(const World& world, BodyId body) {
  std::vector<Sphere> out;
  for (const WorldLeaf& leaf : oracle_leaves(world)) {
    if (leaf.body == body) out.push_back(leaf.sphere);
  }
  return out;
}

TEST(WorldQuery, DistancesAreTheSmallestLeafGap) {
  for (const int tree_depth : {0, 2}) {
    QueryRng rng(19 + tree_depth);
    const World world = random_query_world(rng, 30, 2.5f, tree_depth);
    const WorldQuery query(world);
    for (std::uint32_t a = 0; a < world.body_slots(); ++a) {
      const std::vector<Sphere> leaves_a = leaves_of(world, world.id_of(a));
      for (std::uint32_t b = a + 1; b < world.body_slots(); ++b) {
        const DistanceResult result = query.distance(world.id_of(a), world.id_of(b));
        EXPECT_TRUE(result.exact);
        EXPECT_NEAR(result.distance, oracle_distance(leaves_a, leaves_of(world, world.id_of(b))),
                    kTolerance);
        // The closest pair's points are the gap apart (overlap: crossed by it).
        EXPECT_NEAR((result.point_b - result.point_a).norm(), std::abs(result.distance),
                    kTolerance);
      }
      const Vec3 point = uniform_point(rng, 3.0f);
      const DistanceResult to_point = query.distance(world.id_of(a), point);
      EXPECT_NEAR(to_point.distance, oracle_distance(leaves_a, {{point, 0.0f}}), kTolerance);
      EXPECT_EQ(to_point.point_b, point);
    }
  }
}

TEST(WorldQuery, ABudgetGivesALowerBoundAndSaysSo) {
  QueryRng rng(23);
  const World world = random_query_world(rng, 20, 2.5f);
  const WorldQuery query(world);
  int cut_short = 0;
  for (std::uint32_t a = 0; a < world.body_slots(); ++a) {
    for (std::uint32_t b = a + 1; b < world.body_slots(); ++b) {
      const DistanceResult exact = query.distance(world.id_of(a), world.id_of(b));
      for (const std::uint64_t tests : {1u, 3u, 10u}) {
        const DistanceResult bound =
            query.distance(world.id_of(a), world.id_of(b), {.max_sphere_tests = tests});
        EXPECT_LE(bound.sphere_tests, exact.sphere_tests);
        if (bound.exact) {
          EXPECT_EQ(bound.distance, exact.distance);
        } else {
          ++cut_short;
          EXPECT_LE(bound.distance, exact.distance + 1e-6f);
        }
      }
    }
  }
  EXPECT_GT(cut_short, 50);
}

TEST(WorldQuery, FiltersLeaveOutBodiesBySkipCategoryAndSleep) {
  QueryRng rng(29);
  WorldSettings settings;
  settings.collision.ground_plane_height = 0.0f;
  World world(settings);
  // Balls on the plane fall asleep; one more floats above (no gravity reaches it: static).
  const SphereTreeNode ball_nodes[] = {{{Vec3::Zero(), 0.3f}, -1}, {{Vec3::Zero(), 0.3f}, 0}};
  const auto ball_tree = std::make_shared<const SphereTree>(SphereTree::from_nodes(ball_nodes, 8));
  std::vector<BodyId> balls;
  for (int i = 0; i < 5; ++i) {
    BodyDesc desc;
    desc.tree = ball_tree;
    desc.pose.translation = Vec3(2.0f * float(i), 0.35f, 0.0f);
    balls.push_back(world.add_body(desc));
  }
  for (int i = 0; i < 600; ++i) world.step(1.0f / 60.0f);
  for (const BodyId ball : balls) ASSERT_TRUE(world.asleep(ball));
  BodyDesc lamp;
  lamp.tree = random_query_tree(rng, 4, 2);
  lamp.pose.translation = Vec3(2.0f, 3.0f, 0.0f);
  lamp.is_static = true;
  const BodyId lamp_id = world.add_body(lamp);
  const WorldQuery query(world);

  const std::vector<QueryFilter> filters = [&] {
    std::vector<QueryFilter> out(4);
    out[1].skip = {balls[1], lamp_id};
    out[2].categories = {2, 1, 2, 1, 2, 4};  // per slot: the lamp is slot 5
    out[2].mask = 6;
    out[3].skip_sleeping = true;
    return out;
  }();
  for (const QueryFilter& filter : filters) {
    const auto expected = oracle_overlap(world, filter, [](const Sphere& s) {
      return (s.center - Vec3(2.0f, 1.5f, 0.0f)).norm() <= s.radius + 10.0f;
    });
    EXPECT_EQ(slots(query.overlap_sphere(Vec3(2.0f, 1.5f, 0.0f), 10.0f, filter)), expected);
    // A ray down through the lamp onto ball 1 sees the first body the filter lets through.
    const std::vector<OracleHit> down =
        oracle_ray(world, {Vec3(2.0f, 5.0f, 0.0f), -Vec3::UnitY()}, filter);
    const std::optional<RayHit> hit =
        query.cast_ray({Vec3(2.0f, 5.0f, 0.0f), -Vec3::UnitY()}, filter);
    ASSERT_EQ(hit.has_value(), !down.empty());
    if (hit) {
      EXPECT_EQ(hit->body, down.front().body);
    }
  }
  EXPECT_EQ(slots(query.overlap_sphere(Vec3(2.0f, 1.5f, 0.0f), 10.0f, filters[3])),
            std::set<std::uint32_t>{lamp_id.index});
}

TEST(WorldQuery, BadInputIsAnErrorNamingTheArgument) {
  QueryRng rng(31);
  World world = random_query_world(rng, 5, 1.0f);
  const BodyId removed = world.id_of(4);
  world.remove_body(removed);
  const WorldQuery query(world);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  using testing::HasSubstr;
  EXPECT_THAT(error_message([&] {
                (void)query.cast_ray({Vec3(nan, 0, 0), Vec3::UnitX()});
              }),
              HasSubstr("ray.origin"));
  EXPECT_THAT(error_message([&] {
                (void)query.cast_ray({Vec3::Zero(), Vec3::Zero()});
              }),
              HasSubstr("ray.direction: zero length"));
  EXPECT_THAT(error_message([&] {
                (void)query.cast_ray_all({Vec3::Zero(), Vec3(0, nan, 0)});
              }),
              HasSubstr("ray.direction"));
  EXPECT_THAT(error_message([&] {
                (void)query.cast_ray({Vec3::Zero(), Vec3::UnitX(), -1.0f});
              }),
              HasSubstr("ray.max_distance"));
  EXPECT_THAT(error_message([&] {
                (void)query.cast_ray({Vec3::Zero(), Vec3::UnitX(), nan});
              }),
              HasSubstr("ray.max_distance"));
  EXPECT_THAT(error_message([&] { (void)query.distance(removed, world.id_of(0)); }),
              HasSubstr("body_a: no body with id 4.1"));
  EXPECT_THAT(error_message([&] {
                (void)query.distance(world.id_of(0), BodyId{77, 1});
              }),
              HasSubstr("body_b: no body"));
  EXPECT_THAT(error_message([&] { (void)query.distance(world.id_of(0), BodyId{}); }),
              HasSubstr("body_b: the null body id (BodyId{}) names no body"));
  EXPECT_THAT(error_message([&] { (void)query.distance(world.id_of(0), world.id_of(0)); }),
              HasSubstr("body_b: the same body"));
  EXPECT_THAT(error_message([&] { (void)query.distance(world.id_of(0), Vec3(0, 0, nan)); }),
              HasSubstr("point"));
  QueryFilter stale;
  stale.skip = {removed};
  EXPECT_THAT(error_message([&] { (void)query.overlap_sphere(Vec3::Zero(), 1.0f, stale); }),
              HasSubstr("filter.skip"));
  EXPECT_THAT(error_message([&] { (void)query.overlap_sphere(Vec3::Zero(), -1.0f); }),
              HasSubstr("radius"));
  EXPECT_THAT(error_message([&] {
                (void)query.overlap_aabb({Vec3::Ones(), Vec3::Zero()});
              }),
              HasSubstr("box.max - box.min"));
  OrientedBox bad_box;
  bad_box.pose.rotation.coeffs() = Eigen::Vector4f(1, 1, 0, 0);
  EXPECT_THAT(error_message([&] { (void)query.overlap_box(bad_box); }),
              HasSubstr("box.pose.rotation"));
  EXPECT_THAT(error_message([&] { (void)query.overlap_body(removed, Transform{}); }),
              HasSubstr("body: no body"));
}

TEST(WorldQuery, AnEmptyWorldHasNothingToHit) {
  const World world;
  const WorldQuery query(world);
  EXPECT_FALSE(query.cast_ray({Vec3::Zero(), Vec3::UnitX()}).has_value());
  EXPECT_TRUE(query.overlap_sphere(Vec3::Zero(), 100.0f).empty());
}

}  // namespace
}  // namespace sphys::test
