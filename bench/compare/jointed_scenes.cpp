#include "jointed_scenes.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "sphys/error.h"
#include "sphys/tools/scenarios.h"

namespace sphys::compare {
namespace {

constexpr float kDensity = 1000.0f;    // of every limb. unit: kg/m³
constexpr int kBunnyDepth = 3;         // of the chains' bunnies' sphere-trees. unit: levels
constexpr int kMaxRagdolls = 10'000;   // unit: ragdolls
constexpr int kMaxChainCount = 1'000;  // chains, and links per chain

float real(int count) { return static_cast<float>(count); }

// A capsule along the body's x or y axis, as spheres of its radius spaced at most a radius
// apart, with a solid cylinder's mass properties.
BenchShape capsule(std::string name, int axis, float length, float radius) {
  BenchShape shape;
  shape.name = std::move(name);
  const float inner = length - 2.0f * radius;  // between the end spheres' centres. unit: m
  const int count = static_cast<int>(std::ceil(inner / radius - 1e-4f)) + 1;
  std::vector<SphereTreeNode> nodes = {{Sphere{Vec3::Zero(), 0.5f * length}, -1}};
  for (int i = 0; i < count; ++i) {
    Vec3 centre = Vec3::Zero();
    centre[axis] = count > 1 ? -0.5f * inner + inner * real(i) / real(count - 1) : 0.0f;
    shape.leaves.push_back({centre, radius});
    nodes.push_back({shape.leaves.back(), 0});
  }
  shape.tree = std::make_shared<const SphereTree>(SphereTree::from_nodes(nodes, 8));
  shape.mass = kDensity * std::numbers::pi_v<float> * radius * radius * length;
  const float across = shape.mass * (3.0f * radius * radius + length * length) / 12.0f;
  shape.inertia = Mat3::Identity() * across;
  shape.inertia(axis, axis) = 0.5f * shape.mass * radius * radius;
  shape.max_vertex_distance = 0.5f * length;
  return shape;
}

// Adds a body of `shape` at `pose` to the scene.
void add_body(BenchScene& bench, std::uint32_t shape, const Transform& pose) {
  bench.shape_of.push_back(shape);
  bench.start.push_back(pose);
}

// A hinge or ball joint through the world point `at` (unit: m) between bodies a (the parent;
// none: the world) and b, its axis `axis` in the world, from the bodies' start poses.
tools::JointSpec joint_at(const BenchScene& bench, std::optional<std::size_t> a, std::size_t b,
                          JointType type, const Vec3& at, const Vec3& axis) {
  tools::JointSpec joint;
  joint.body_a = a;
  joint.body_b = b;
  joint.desc.type = type;
  const Transform world_a = a ? bench.start[*a] : Transform{};
  const Transform& world_b = bench.start[b];
  joint.desc.anchor_a = world_a.rotation.conjugate() * (at - world_a.translation);
  joint.desc.anchor_b = world_b.rotation.conjugate() * (at - world_b.translation);
  joint.desc.axis_a = world_a.rotation.conjugate() * axis;
  joint.desc.axis_b = world_b.rotation.conjugate() * axis;
  return joint;
}

JointLimit limits(float bound) { return {.enabled = true, .lower = -bound, .upper = bound}; }

// One limb of the ragdoll standing in its own frame (y up, feet at y ≈ 0, arms out along x).
struct Limb {
  std::uint32_t shape;
  Vec3 centre;  // unit: m
};
// One joint of the ragdoll: its parent and child limb, where and about which axis (its twist
// axis for a ball), and its limits (unit: rad): a hinge's angle, a ball's cone and twist.
struct RagdollJoint {
  int parent;
  int child;
  JointType type;
  Vec3 at;  // unit: m
  Vec3 axis;
  float bound;  // hinge angle, ball twist. unit: rad
  float cone;   // ball swing. unit: rad
};

BenchScene ragdolls(int count) {
  BenchScene bench = bunny_bench_scene("ragdolls:" + std::to_string(count), tools::Scene{}, 2);
  // Shapes: name, axis (0: x, 1: y), length and radius (unit: m).
  bench.shapes = {capsule("pelvis", 0, 0.34f, 0.11f),   capsule("chest", 0, 0.38f, 0.13f),
                  capsule("head", 1, 0.24f, 0.11f),     capsule("upper arm", 0, 0.28f, 0.05f),
                  capsule("forearm", 0, 0.28f, 0.045f), capsule("thigh", 1, 0.40f, 0.07f),
                  capsule("shin", 1, 0.40f, 0.055f)};
  const std::vector<Limb> limbs = {
      {0, {0.0f, 1.00f, 0.0f}},   {1, {0.0f, 1.32f, 0.0f}},   {2, {0.0f, 1.64f, 0.0f}},
      {3, {-0.36f, 1.36f, 0.0f}}, {4, {-0.64f, 1.36f, 0.0f}}, {3, {0.36f, 1.36f, 0.0f}},
      {4, {0.64f, 1.36f, 0.0f}},  {5, {-0.1f, 0.68f, 0.0f}},  {6, {-0.1f, 0.26f, 0.0f}},
      {5, {0.1f, 0.68f, 0.0f}},   {6, {0.1f, 0.26f, 0.0f}}};
  const Vec3 x = Vec3::UnitX();
  const Vec3 y = Vec3::UnitY();
  const JointType ball = JointType::kBall;
  const JointType hinge = JointType::kHinge;
  const std::vector<RagdollJoint> joints = {
      {0, 1, ball, {0.0f, 1.17f, 0.0f}, y, 0.4f, 0.5f},     // waist
      {1, 2, ball, {0.0f, 1.50f, 0.0f}, y, 0.6f, 0.6f},     // neck
      {1, 3, ball, {-0.22f, 1.36f, 0.0f}, x, 0.8f, 1.3f},   // shoulders
      {1, 5, ball, {0.22f, 1.36f, 0.0f}, x, 0.8f, 1.3f},    //
      {3, 4, hinge, {-0.50f, 1.36f, 0.0f}, y, 1.3f, 0.0f},  // elbows
      {5, 6, hinge, {0.50f, 1.36f, 0.0f}, y, 1.3f, 0.0f},   //
      {0, 7, ball, {-0.1f, 0.89f, 0.0f}, y, 0.4f, 0.9f},    // hips
      {0, 9, ball, {0.1f, 0.89f, 0.0f}, y, 0.4f, 0.9f},     //
      {7, 8, hinge, {-0.1f, 0.47f, 0.0f}, x, 1.3f, 0.0f},   // knees
      {9, 10, hinge, {0.1f, 0.47f, 0.0f}, x, 1.3f, 0.0f}};
  // Layers of 5 × 5 ragdolls lying face down, 2.5 m apart (an arm's span and more) and 0.5 m
  // above each other, each turned about the vertical by an angle of the stacks' sequence.
  constexpr int kPerRow = 5;
  constexpr float kSpacing = 2.5f;       // unit: m
  constexpr float kFirstHeight = 0.5f;   // unit: m
  constexpr float kLayerSpacing = 0.5f;  // unit: m
  const Vec3 middle(0.0f, 0.9f, 0.0f);   // of the standing ragdoll, where it turns. unit: m
  tools::SplitMix64 random(tools::kStacksSeed);
  for (int r = 0; r < count; ++r) {
    const int layer = r / (kPerRow * kPerRow);
    const int row = (r / kPerRow) % kPerRow;
    const int column = r % kPerRow;
    const Vec3 place((real(column) - 0.5f * real(kPerRow - 1)) * kSpacing,
                     kFirstHeight + kLayerSpacing * real(layer),
                     (real(row) - 0.5f * real(kPerRow - 1)) * kSpacing);
    const auto yaw = static_cast<float>(2.0 * std::numbers::pi * random.next_unit());
    const Quat turn = Quat(Eigen::AngleAxisf(yaw, y)) *
                      Quat(Eigen::AngleAxisf(0.5f * std::numbers::pi_v<float>, x));
    const std::size_t first = bench.start.size();
    for (const Limb& limb : limbs) {
      add_body(bench, limb.shape, Transform{turn, place + turn * (limb.centre - middle)});
    }
    for (const RagdollJoint& j : joints) {
      tools::JointSpec joint = joint_at(bench, first + j.parent, first + j.child, j.type,
                                        place + turn * (j.at - middle), turn * j.axis);
      joint.desc.limit = limits(j.bound);  // a hinge's angle, a ball's twist
      if (j.type == ball) joint.desc.cone = {.enabled = true, .angle = j.cone};
      bench.joints.push_back(joint);
    }
  }
  return bench;
}

BenchScene chains(int count, int links) {
  // The pile: 3 rows of bunnies across the chains' sweep under their pivots, 1.5 m apart as the
  // stacks, two high, turned as the stacks.
  constexpr float kLinkLength = 0.25f;   // unit: m
  constexpr float kChainSpacing = 0.6f;  // between neighbouring chains. unit: m
  constexpr float kBunnySpacing = 1.5f;  // unit: m
  const float width = kChainSpacing * real(count - 1);
  const int across = static_cast<int>(std::floor(width / kBunnySpacing)) + 1;
  tools::Scene pile = tools::bunny_stacks_scene(1, 1, kBunnyDepth);
  const tools::BodySpec bunny = pile.bodies.front();
  pile.bodies.clear();
  tools::SplitMix64 random(tools::kStacksSeed);
  for (int level = 0; level < 2; ++level) {
    for (int row = 0; row < 3; ++row) {
      for (int k = 0; k < across; ++k) {
        tools::BodySpec body = bunny;
        body.position = Vec3(real(row - 1) * kBunnySpacing, 1.0f + 1.2f * real(level),
                             (real(k) - 0.5f * real(across - 1)) * kBunnySpacing);
        const auto angle = static_cast<float>(2.0 * std::numbers::pi * random.next_unit());
        body.orientation = Quat(Eigen::AngleAxisf(angle, Vec3::UnitY()));
        pile.bodies.push_back(body);
      }
    }
  }
  BenchScene bench =
      bunny_bench_scene("chains:" + std::to_string(count) + "x" + std::to_string(links),
                        std::move(pile), kBunnyDepth);
  const auto link = static_cast<std::uint32_t>(bench.shapes.size());
  bench.shapes.push_back(capsule("link", 0, kLinkLength, 0.05f));
  // The pivots high enough that a hanging chain's end is 1.5 m above the plane.
  const float pivot_height = kLinkLength * real(links) + 1.5f;
  for (int c = 0; c < count; ++c) {
    const float z = -0.5f * width + kChainSpacing * real(c);
    for (int i = 0; i < links; ++i) {
      const std::size_t body = bench.start.size();
      add_body(bench, link,
               Transform{Quat::Identity(), Vec3(kLinkLength * (real(i) + 0.5f), pivot_height, z)});
      const std::optional<std::size_t> parent =
          i == 0 ? std::nullopt : std::optional<std::size_t>(body - 1);
      tools::JointSpec joint =
          joint_at(bench, parent, body, JointType::kHinge,
                   Vec3(kLinkLength * real(i), pivot_height, z), Vec3::UnitZ());
      // The pivot lets the chain fall from level to hanging and beyond; the links bend 1 rad.
      joint.desc.limit = limits(i == 0 ? 2.5f : 1.0f);
      bench.joints.push_back(joint);
    }
  }
  return bench;
}

int counted(std::istringstream& in, int most, const std::string& name, const char* forms) {
  int value = 0;
  if (!(in >> value) || value < 1 || value > most) {
    throw Error("jointed scene '" + name + "': " + forms + ", each count 1 to " +
                std::to_string(most));
  }
  return value;
}

}  // namespace

float twist_span(const JointDesc& ball) {
  if (!ball.limit.enabled) return std::numbers::pi_v<float>;
  return std::max(std::abs(ball.limit.lower), std::abs(ball.limit.upper));
}

bool is_jointed_scene(const std::string& name) {
  return name.starts_with("ragdolls:") || name.starts_with("chains:");
}

BenchScene make_jointed_scene(const std::string& name) {
  constexpr const char* kForms = "the forms are ragdolls:R and chains:CxL";
  const auto colon = name.find(':');
  std::istringstream in(colon == std::string::npos ? std::string() : name.substr(colon + 1));
  if (name.starts_with("ragdolls:")) {
    const int count = counted(in, kMaxRagdolls, name, kForms);
    if (in.peek() == std::char_traits<char>::eof()) return ragdolls(count);
  } else if (name.starts_with("chains:")) {
    const int count = counted(in, kMaxChainCount, name, kForms);
    if (in.get() == 'x') {
      const int links = counted(in, kMaxChainCount, name, kForms);
      if (in.peek() == std::char_traits<char>::eof()) return chains(count, links);
    }
  }
  throw Error("jointed scene '" + name + "': " + kForms);
}

}  // namespace sphys::compare
