#pragma once

// The benchmark scenes of every engine, described once: bodies of a few shapes (each a set of
// leaf spheres with its mass properties), their starting poses, the joints between them, over
// the plane y = 0, 1/60 s steps, restitution 0.3 and friction 0.5 on every contact.
//
// - "SxN": S stacks of N bunnies (bunny_stacks_scene), one bunny model from sphys: its mass
//   properties and the leaf spheres of its sphere-tree.
// - the jointed scenes (jointed_scenes.h): ragdolls and chains of limbs made of spheres, joined
//   by hinges and ball joints with limits, some falling into bunnies.
// - the arm scene (robot_scene.h): a robot under position control sweeping through a pile.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_robot.h"
#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::compare {

// One shape of the scene's bodies, in its body frame (centre of mass at the origin).
struct BenchShape {
  std::string name;
  float mass = 0.0f;                 // unit: kg
  Mat3 inertia = Mat3::Identity();   // about the centre of mass, body axes. unit: kg·m²
  std::vector<Sphere> leaves;        // the leaves of its sphere-tree, body frame. unit: m
  float max_vertex_distance = 0.0f;  // r_max of the moving-body test. unit: m
  // The bunny's mesh (its convex hull for bullet-hull); none for a shape made of spheres.
  std::optional<tools::TriangleMesh> mesh;
  // The sphere-tree sphys gives a body of this shape that the bunnies' tools::Scene does not
  // build (a limb: its leaves under one root).
  std::shared_ptr<const SphereTree> tree;
};

struct BenchScene {
  std::string name;  // as the tables head it: "4x25", "ragdolls:100", "chains:20x20"
  // What sphys builds with tools::build_world: the bunnies (the scene's first bodies) over the
  // exact plane, and the world's settings. Bodies after them are added from their shape's tree.
  tools::Scene scene;
  int depth = 0;                  // of the bunnies' sphere-trees (a limb's tree has 2 levels)
  double time_step = 1.0 / 60.0;  // unit: s
  float restitution = 0.3f;
  float friction = 0.5f;

  std::vector<BenchShape> shapes;
  std::vector<std::uint32_t> shape_of;  // per body: its index into shapes
  std::vector<Transform> start;         // per body
  // Hinges and ball joints, body b the child of body a (or of the world): every body is the
  // body b of one joint at most and the joints make trees, as MuJoCo's bodies. The joints'
  // anchors and axes are in the body frames above.
  std::vector<tools::JointSpec> joints;
  // A robot, whose bodies and joints are among the above: its bodies' start poses are at every
  // joint 0, and each engine places it at its motion's first waypoint.
  std::optional<BenchRobot> robot;
  // How many frames a run takes, for a scene with a length of its own (the arm's motion); 0: as
  // many as sphys-compare's --frames.
  int frames = 0;

  [[nodiscard]] const BenchShape& shape(std::size_t body) const { return shapes[shape_of[body]]; }
};

// S stacks of N bunnies. Builds the bunny's tree (or takes it from the sphere-tree cache).
// Throws sphys::Error for counts or a depth out of range.
[[nodiscard]] BenchScene make_bench_scene(int stacks, int per_stack, int depth);

// The bunny shape and the scene's plane, restitution and friction over `bunnies`: what every
// scene with bunnies shares. The scene's bodies and shapes are the bunnies (shape 0).
[[nodiscard]] BenchScene bunny_bench_scene(std::string name, tools::Scene bunnies, int depth);

}  // namespace sphys::compare
