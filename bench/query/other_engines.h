#pragma once

// The engines the queries are compared with, each in its own file so that their headers stay
// there: Bullet's rayTest and contactTest on the comparison's sphere compounds (bullet_scene.cpp),
// and FCL, what MoveIt checks with, on the meshes (fcl_checks.cpp).

#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "sphys/math.h"
#include "sphys/sphere_tree.h"
#include "sphys/tools/triangle_mesh.h"

namespace sphys::query_bench {

// Bunnies as Bullet compounds of their leaf spheres, static, in a btCollisionWorld (dynamic AABB
// tree broad phase): rayTest for rays, contactTest for a robot's spheres (one compound whose
// children move to each configuration's places).
class BulletScene {
 public:
  BulletScene(const std::vector<Sphere>& leaves, std::span<const Transform> poses,
              std::span<const float> robot_radii);
  ~BulletScene();
  struct Hit {
    int body = -1;                                            // index into the poses, -1 for none
    float distance = std::numeric_limits<float>::infinity();  // unit: m
  };
  // The nearest hit of the segment from `origin` along the unit `direction`, `length` long.
  [[nodiscard]] Hit cast(const Vec3& origin, const Vec3& direction, float length) const;
  // Whether the robot's spheres (x, y, z, radius each, the radii those given at construction)
  // touch a bunny's: contactTest of the robot's compound against the world.
  [[nodiscard]] bool touches(std::span<const float> spheres) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Bunnies' meshes in FCL BVHs (OBBRSS) under a dynamic AABB tree manager, and a robot's link
// meshes, checked link by link against them.
class FclScene {
 public:
  FclScene(const tools::TriangleMesh& bunny, std::span<const Transform> poses,
           const std::vector<tools::TriangleMesh>& link_meshes);
  ~FclScene();
  // Whether a link mesh at its pose (one per link mesh) touches a bunny's mesh.
  [[nodiscard]] bool collides(std::span<const Transform> link_poses) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sphys::query_bench
