#include "collision/collision_detector.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"
#include "sphys/tools/primitives.h"

namespace sphys {
namespace {

using Key = std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t>;

std::shared_ptr<const SphereTree> octree_of(const tools::TriangleMesh& mesh, int depth) {
  tools::BuildOptions options;
  options.method = tools::BuildMethod::Octree;
  options.depth = depth;
  return std::make_shared<const SphereTree>(tools::build_sphere_tree(mesh, options));
}

struct Scene {
  std::vector<std::shared_ptr<const SphereTree>> trees;
  std::vector<Transform> poses;
  std::vector<bool> is_static;
};

// Nodes that are leaves when the tree is used to `depth` levels (0: all).
std::vector<std::uint32_t> used_leaves(const SphereTree& tree, int depth) {
  const int last = (depth <= 0 || depth > tree.depth()) ? tree.depth() - 1 : depth - 1;
  std::vector<std::uint32_t> leaves;
  for (std::uint32_t n = 0; n < tree.level_end(last); ++n) {
    if (tree.is_leaf(n) || n >= tree.level_begin(last)) leaves.push_back(n);
  }
  return leaves;
}

// The oracle: every leaf pair of every body pair (not both static) apart by at most `gap`, tested
// directly; and every leaf within `gap` of the ground plane.
std::set<Key> brute_force(const Scene& scene, int depth, std::optional<float> ground,
                          float gap = 0.0f) {
  std::set<Key> keys;
  for (std::uint32_t a = 0; a < scene.trees.size(); ++a) {
    for (std::uint32_t b = a + 1; b < scene.trees.size(); ++b) {
      if (scene.is_static[a] && scene.is_static[b]) continue;
      for (std::uint32_t la : used_leaves(*scene.trees[a], depth)) {
        for (std::uint32_t lb : used_leaves(*scene.trees[b], depth)) {
          const Sphere& sa = scene.trees[a]->sphere(la);
          const Sphere& sb = scene.trees[b]->sphere(lb);
          if (spheres_overlap(scene.poses[a].apply(sa.center), sa.radius + gap,
                              scene.poses[b].apply(sb.center), sb.radius)) {
            keys.insert({a, b, la, lb});
          }
        }
      }
    }
    if (ground && !scene.is_static[a]) {
      for (std::uint32_t l : used_leaves(*scene.trees[a], depth)) {
        const Sphere& s = scene.trees[a]->sphere(l);
        if (scene.poses[a].apply(s.center).y() - s.radius <= *ground + gap) {
          keys.insert({kGroundPlaneBody, a, 0, l});
        }
      }
    }
  }
  return keys;
}

// Body pairs in increasing order (the ground plane first), each contact once.
std::set<Key> keys_of(const std::vector<Contact>& contacts) {
  std::set<Key> keys;
  for (const Contact& c : contacts) {
    const bool in_order = c.body_a == kGroundPlaneBody || c.body_a < c.body_b;
    const Key key = in_order ? Key{c.body_a, c.body_b, c.leaf_a, c.leaf_b}
                             : Key{c.body_b, c.body_a, c.leaf_b, c.leaf_a};
    EXPECT_TRUE(keys.insert(key).second) << "a contact appears twice";
  }
  return keys;
}

// A detector over a body store of its own, as a world sets one up.
struct Detection {
  BodyStore store;
  CollisionDetector detector;

  explicit Detection(const DetectorSettings& settings = {}) : detector(settings) {
    detector.set_bodies(store);
  }
  Detection(const Detection&) = delete;
  Detection& operator=(const Detection&) = delete;

  std::uint32_t add(std::shared_ptr<const SphereTree> tree, const Transform& pose, bool is_static) {
    RigidBody body;
    body.pose = pose;
    body.is_static = is_static;
    body.inverse_mass = 1.0f;
    const float extent = tree ? tree->root().center.norm() + tree->subtree_radius(0) : 0.0f;
    const std::uint32_t slot = store.add(body, extent);
    detector.add_body(slot, std::move(tree));
    return slot;
  }
  void remove(std::uint32_t slot) {
    detector.remove_body(slot);
    store.remove(slot);
  }
};

// detect(), with the contacts copied out.
const CollisionStats& detect_into(CollisionDetector& detector, std::vector<Contact>& contacts) {
  const CollisionStats& stats = detector.detect();
  contacts.assign(detector.contacts().begin(), detector.contacts().end());
  return stats;
}

Transform random_pose(std::mt19937_64& rng, float spread) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Transform pose;
  pose.rotation = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
  pose.translation = Vec3(u(rng), u(rng) * 0.5f + 0.5f, u(rng)) * spread;
  return pose;
}

TEST(CollisionDetector, ContactsEqualBruteForceOverManySteps) {
  const auto torus = octree_of(tools::make_torus(0.5, 0.15, 24, 12), 3);
  const auto box = octree_of(tools::make_box({0.6, 0.3, 0.4}), 3);
  std::mt19937_64 rng(2008);
  for (int depth : {0, 2}) {
    Scene scene;
    DetectorSettings settings;
    settings.tree_depth = depth;
    settings.ground_plane_height = 0.1f;
    Detection detection(settings);
    CollisionDetector& detector = detection.detector;
    std::vector<std::uint32_t> ids;
    for (int i = 0; i < 24; ++i) {
      scene.trees.push_back(i % 2 ? torus : box);
      scene.poses.push_back(random_pose(rng, 2.0f));
      scene.is_static.push_back(i % 7 == 0);
      ids.push_back(detection.add(scene.trees.back(), scene.poses.back(), scene.is_static.back()));
    }
    std::vector<Contact> contacts;
    for (int step = 0; step < 20; ++step) {
      for (std::size_t i = 0; i < ids.size(); ++i) {
        if (scene.is_static[i]) continue;
        // Mostly small moves (temporal coherence), now and then a jump.
        Transform& pose = scene.poses[i];
        if (step % 7 == 3 && i % 3 == 0) {
          pose = random_pose(rng, 2.0f);
        } else {
          const Transform nudge = random_pose(rng, 0.05f);
          pose.translation += nudge.translation - Vec3(0, 0.025f, 0);
          pose.rotation =
              (pose.rotation * Quat::Identity().slerp(0.05f, nudge.rotation)).normalized();
        }
        detection.store.poses()[ids[i]] = pose;
        detection.detector.bound_at_pose(ids[i]);
      }
      const CollisionStats& stats = detect_into(detector, contacts);
      const std::set<Key> expected = brute_force(scene, depth, settings.ground_plane_height);
      ASSERT_EQ(keys_of(contacts), expected) << "depth " << depth << " step " << step;
      EXPECT_EQ(stats.contacts, contacts.size());
      EXPECT_EQ(stats.leaf_pairs, contacts.size());
      EXPECT_EQ(stats.pairs_cut_short, 0u);
      EXPECT_EQ(stats.bodies, 24u);
    }
  }
}

// Pairs that barely moved keep their leaf pairs instead of descending: no leaf pair within the gap
// may be missed, and each kept contact is the exact contact of its leaf pair at the new poses.
TEST(CollisionDetector, ReusedPairsMissNoLeafPairWithinTheGap) {
  const auto torus = octree_of(tools::make_torus(0.5, 0.15, 24, 12), 3);
  const auto box = octree_of(tools::make_box({0.6, 0.3, 0.4}), 3);
  std::mt19937_64 rng(16);
  Scene scene;
  DetectorSettings settings;
  settings.ground_plane_height = 0.1f;
  settings.contact_margin = 0.02f;
  settings.reuse_distance = 0.004f;
  Detection detection(settings);
  CollisionDetector& detector = detection.detector;
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < 16; ++i) {
    scene.trees.push_back(i % 2 ? torus : box);
    scene.poses.push_back(random_pose(rng, 1.2f));
    scene.is_static.push_back(i % 7 == 0);
    ids.push_back(detection.add(scene.trees.back(), scene.poses.back(), scene.is_static.back()));
  }
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Contact> contacts;
  std::uint32_t reused = 0;
  std::uint32_t descended = 0;
  for (int step = 0; step < 40; ++step) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (scene.is_static[i]) continue;
      // Creeping by up to 1.5 mm a step, so pairs are reused for a step or two and then, having
      // moved beyond the reuse distance since their descent, descend again.
      Transform& pose = scene.poses[i];
      pose.translation += 0.0015f * Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0f);
      pose.rotation =
          (pose.rotation * Quat(Eigen::AngleAxisf(0.001f * u(rng), Vec3::UnitY()))).normalized();
      detection.store.poses()[ids[i]] = pose;
      detection.detector.bound_at_pose(ids[i]);
    }
    const CollisionStats& stats = detect_into(detector, contacts);
    reused += stats.reused_pairs;
    descended += stats.descended_pairs;
    const std::set<Key> found = keys_of(contacts);
    for (const Key& key :
         brute_force(scene, 0, settings.ground_plane_height, settings.contact_margin)) {
      ASSERT_TRUE(found.contains(key))
          << "step " << step << ": a leaf pair within the gap is missing";
    }
    for (const Contact& c : contacts) {
      Contact exact = c;
      const Sphere& sb = scene.trees[c.body_b]->sphere(c.leaf_b);
      const Sphere world_b{scene.poses[c.body_b].apply(sb.center), sb.radius};
      if (c.body_a == kGroundPlaneBody) {
        sphere_plane_contact(*settings.ground_plane_height, world_b, exact);
      } else {
        const Sphere& sa = scene.trees[c.body_a]->sphere(c.leaf_a);
        const Sphere world_a{scene.poses[c.body_a].apply(sa.center), sa.radius};
        (void)sphere_sphere_contact(world_a, world_b, Vec3::UnitY(), exact);
      }
      ASSERT_NEAR(c.depth, exact.depth, 1e-5f);
      ASSERT_TRUE(c.point.isApprox(exact.point, 1e-4f));
      // Reported within the gap plus the reuse distance, then moved by up to that again.
      ASSERT_GE(c.depth, -(settings.contact_margin + 2.0f * settings.reuse_distance) - 1e-5f);
    }
  }
  EXPECT_GT(reused, 0u);
  EXPECT_GT(descended, 0u);
}

TEST(CollisionDetector, ContactsFollowThePaperEquations) {
  // Two single-sphere bodies: the contact is eq. 1-3 of the paper.
  const auto small = std::make_shared<const SphereTree>(
      SphereTree::from_nodes(std::vector<SphereTreeNode>{{{Vec3::Zero(), 1.0f}, -1}}, 8));
  const auto large = std::make_shared<const SphereTree>(
      SphereTree::from_nodes(std::vector<SphereTreeNode>{{{Vec3::Zero(), 3.0f}, -1}}, 8));
  Detection detection;
  CollisionDetector& detector = detection.detector;
  Transform pa;
  Transform pb;
  pb.translation = Vec3(3.0f, 0, 0);
  detection.add(small, pa, false);
  detection.add(large, pb, false);
  std::vector<Contact> contacts;
  detect_into(detector, contacts);
  ASSERT_EQ(contacts.size(), 1u);
  const Contact& c = contacts.front();
  EXPECT_FLOAT_EQ(c.depth, 1.0f);                    // 1 + 3 - 3
  EXPECT_TRUE(c.normal.isApprox(Vec3(1, 0, 0)));     // from a to b
  EXPECT_TRUE(c.point.isApprox(Vec3(0.75f, 0, 0)));  // C1 + r1/(r1+r2)·v
}

TEST(CollisionDetector, TimeCriticalBudgetCutsPairsShortAndStaysValid) {
  const auto torus = octree_of(tools::make_torus(0.5, 0.15, 24, 12), 4);
  DetectorSettings settings;
  settings.max_sphere_tests = 50;
  Detection detection(settings);
  CollisionDetector& detector = detection.detector;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 8; ++i) detection.add(torus, random_pose(rng, 0.4f), false);
  std::vector<Contact> contacts;
  const CollisionStats stats = detect_into(detector, contacts);
  EXPECT_GT(stats.pairs_cut_short, 0u);
  EXPECT_GT(contacts.size(), 0u);
  for (const Contact& c : contacts) EXPECT_GE(c.depth, -1e-5f);  // only overlapping spheres

  settings.max_sphere_tests = 0;  // off: exact again
  detector.set_settings(settings);
  const CollisionStats exact = detect_into(detector, contacts);
  EXPECT_EQ(exact.pairs_cut_short, 0u);
  EXPECT_EQ(exact.leaf_pairs, contacts.size());
}

// Two dynamic bodies that touched and no longer do are counted as parted, whether the narrow
// phase or the broad phase finds them apart; a dynamic body leaving a static one is not.
// The part a node lies in: its ancestor on the first level below the root.
std::uint32_t part_of(const SphereTree& tree, std::uint32_t node) {
  while (tree.level(node) > 1) node = static_cast<std::uint32_t>(tree.parent(node));
  return node;
}

TEST(CollisionDetector, AFastPairIsReducedByPartsAndASlowOneToAManifold) {
  const auto box = octree_of(tools::make_box({0.6, 0.3, 0.4}), 3);
  DetectorSettings settings;
  settings.ground_plane_height = 0.0f;
  settings.contact_margin = 0.02f;
  settings.speculative = true;
  settings.manifold_points = 4;
  settings.fast_pair_reach = 0.03f;
  Detection detection(settings);
  Transform pose_a;
  pose_a.translation = Vec3(0, 0.16f, 0);
  Transform pose_b;
  pose_b.translation = Vec3(0.1f, 0.45f, 0.05f);
  pose_b.rotation = Quat(Eigen::AngleAxisf(0.3f, Vec3::UnitY()));
  Transform pose_c;  // far from both, over the plane
  pose_c.translation = Vec3(3, 0.3f, 0);
  const std::uint32_t a = detection.add(box, pose_a, false);
  const std::uint32_t b = detection.add(box, pose_b, false);
  const std::uint32_t c = detection.add(box, pose_c, false);
  const auto count = [&](std::span<const Contact> contacts, std::uint32_t one,
                         std::uint32_t other) {
    return std::count_if(contacts.begin(), contacts.end(), [&](const Contact& k) {
      return (k.body_a == one && k.body_b == other) || (k.body_a == other && k.body_b == one);
    });
  };
  std::vector<Contact> contacts;

  // At rest every pair is a manifold of at most four points.
  detect_into(detection.detector, contacts);
  ASSERT_GT(count(contacts, a, b), 0);
  EXPECT_LE(count(contacts, a, b), 4);
  EXPECT_LE(count(contacts, kGroundPlaneBody, a), 4);

  // b closes on a, and c on the plane, by 20 cm this step.
  const float closing = 0.2f;
  detection.detector.set_motion(b, Vec3(0, -closing, 0), 0.0f);
  detection.detector.set_motion(c, Vec3(0, -closing, 0), 0.0f);
  detect_into(detection.detector, contacts);
  const float gap = settings.contact_margin + closing;
  // The oracle: per pair of parts, the deepest of its leaf pairs within the gap and how many there
  // are (a's leaf first).
  std::map<std::pair<std::uint32_t, std::uint32_t>, float> deepest;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> leaf_pairs;
  for (const std::uint32_t la : used_leaves(*box, 0)) {
    for (const std::uint32_t lb : used_leaves(*box, 0)) {
      const Sphere& sa = box->sphere(la);
      const Sphere& sb = box->sphere(lb);
      const float depth =
          sa.radius + sb.radius - (pose_a.apply(sa.center) - pose_b.apply(sb.center)).norm();
      if (depth < -gap) continue;
      const auto key = std::pair(part_of(*box, la), part_of(*box, lb));
      const auto found = deepest.find(key);
      if (found == deepest.end() || depth > found->second) deepest[key] = depth;
      ++leaf_pairs[key];
    }
  }
  ASSERT_GT(deepest.size(), 4u) << "too few parts meet for the test to tell";
  // Each pair of parts that meet: two contacts (one where it has a single leaf pair), one of them
  // as deep as its deepest leaf pair.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> seen;
  std::map<std::pair<std::uint32_t, std::uint32_t>, float> deepest_made;
  for (const Contact& k : contacts) {
    if (k.body_a == kGroundPlaneBody || k.body_a == c || k.body_b == c) continue;
    const bool a_first = k.body_a == a;
    const std::uint32_t leaf_a = a_first ? k.leaf_a : k.leaf_b;
    const std::uint32_t leaf_b = a_first ? k.leaf_b : k.leaf_a;
    const auto key = std::pair(part_of(*box, leaf_a), part_of(*box, leaf_b));
    ASSERT_TRUE(deepest.contains(key)) << "a contact between parts that do not meet";
    deepest_made[key] = seen[key]++ == 0 ? k.depth : std::max(deepest_made[key], k.depth);
  }
  EXPECT_EQ(seen.size(), deepest.size());
  for (const auto& [key, contacts_made] : seen) {
    EXPECT_EQ(contacts_made, std::min(2, leaf_pairs[key]));
    EXPECT_NEAR(deepest_made[key], deepest[key], 1e-5f);
  }
  EXPECT_LE(count(contacts, kGroundPlaneBody, a), 4);
  // Against the plane, whose contacts share its normal, c keeps a manifold however fast.
  std::size_t near_plane = 0;
  for (const std::uint32_t leaf : used_leaves(*box, 0)) {
    const Sphere& sphere = box->sphere(leaf);
    if (pose_c.apply(sphere.center).y() - sphere.radius <= gap) ++near_plane;
  }
  EXPECT_GT(near_plane, 4u);
  EXPECT_EQ(count(contacts, kGroundPlaneBody, c), 4);
}

TEST(CollisionDetector, CountsDynamicPairsThatPart) {
  const auto box = octree_of(tools::make_box({1, 1, 1}), 2);
  Detection detection;
  CollisionDetector& detector = detection.detector;
  const std::uint32_t a = detection.add(box, Transform{}, false);
  Transform beside;
  beside.translation = Vec3(0.9f, 0.0f, 0.0f);
  const std::uint32_t b = detection.add(box, beside, false);
  Transform below;
  below.translation = Vec3(0.0f, -0.9f, 0.0f);
  detection.add(box, below, true);
  EXPECT_EQ(detector.detect().parted_pairs, 0u);
  ASSERT_GT(detector.contacts().size(), 0u);
  // Bounds still overlapping (the boxes' spheres stick out), leaf spheres apart: the narrow
  // phase parts them.
  detection.store.poses()[b].translation.x() = 1.5f;
  detection.detector.bound_at_pose(b);
  const CollisionStats parted = detector.detect();
  EXPECT_EQ(parted.parted_pairs, 1u);
  // Every pair of the three still a candidate, and descended: a and b are apart by their leaves.
  EXPECT_EQ(parted.candidate_pairs, 3u);
  EXPECT_EQ(parted.descended_pairs, 3u);
  EXPECT_EQ(detector.detect().parted_pairs, 0u);  // counted once
  detection.store.poses()[b].translation.x() = 0.9f;
  detection.detector.bound_at_pose(b);
  EXPECT_EQ(detector.detect().parted_pairs, 0u);
  // Far apart: the broad phase drops the pair.
  detection.store.poses()[b].translation.x() = 5.0f;
  detection.detector.bound_at_pose(b);
  EXPECT_EQ(detector.detect().parted_pairs, 1u);
  // Body a leaves the static box below it: no island joined them.
  detection.store.poses()[a].translation.y() = 5.0f;
  detection.detector.bound_at_pose(a);
  EXPECT_EQ(detector.detect().parted_pairs, 0u);
}

TEST(CollisionDetector, RemovedBodiesLeaveNoContacts) {
  const auto box = octree_of(tools::make_box({1, 1, 1}), 2);
  Detection detection;
  CollisionDetector& detector = detection.detector;
  detection.add(box, Transform{}, false);
  const std::uint32_t b = detection.add(box, Transform{}, false);
  std::vector<Contact> contacts;
  detect_into(detector, contacts);
  EXPECT_GT(contacts.size(), 0u);
  detection.remove(b);
  detect_into(detector, contacts);
  EXPECT_TRUE(contacts.empty());
  EXPECT_EQ(detection.add(box, Transform{}, true), b);  // the freed slot, static now
  detect_into(detector, contacts);
  EXPECT_GT(contacts.size(), 0u);
  EXPECT_THROW((void)detection.add(nullptr, Transform{}, false), Error);
  Transform bad;
  bad.translation.x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW((void)detection.add(box, bad, false), Error);
}

}  // namespace
}  // namespace sphys
