#pragma once

// The benchmark scene of every engine (S stacks of N bunnies over the plane y = 0, 1/60 s steps,
// restitution 0.3 and friction 0.5 on every contact): one bunny model, its mass properties and
// leaf spheres from sphys, and the starting poses.

#include <cstdint>
#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::compare {

struct BenchScene {
  tools::Scene scene;  // what sphys runs: the stacks over the exact plane
  int stacks = 0;
  int per_stack = 0;
  int depth = 0;
  double time_step = 1.0 / 60.0;  // unit: s
  float restitution = 0.3f;
  float friction = 0.5f;

  // The bunny, in its body frame (centre of mass at the origin, mesh axes).
  tools::TriangleMesh mesh;
  float mass = 0.0f;                 // unit: kg
  Mat3 inertia = Mat3::Identity();   // about the centre of mass, body axes. unit: kg·m²
  std::vector<Sphere> leaves;        // of its sphere-tree at `depth`, body frame. unit: m
  float max_vertex_distance = 0.0f;  // r_max of the moving-body test. unit: m

  std::vector<Transform> start;  // per body
};

// Builds the bunny's tree (or takes it from the sphere-tree cache). Throws sphys::Error for
// counts or a depth out of range.
[[nodiscard]] BenchScene make_bench_scene(int stacks, int per_stack, int depth);

}  // namespace sphys::compare
