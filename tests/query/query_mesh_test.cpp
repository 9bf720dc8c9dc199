// Queries are conservative for the meshes under sphys-built trees: where a ray meets a mesh,
// the query hits no farther; a shape holding a point of a body's surface overlaps the body; and
// the leaf spheres' gap is never more than the meshes' distance.

#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "sphys/tools/build_tree.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/primitives.h"
#include "sphys/world_query.h"
#include "support/query_worlds.h"

namespace sphys::test {
namespace {

using tools::TriangleMesh;
using tools::Vec3d;

struct MeshWorld {
  TriangleMesh mesh;  // every body's, in the body frame
  std::shared_ptr<const SphereTree> tree;
  std::vector<Transform> poses;
  World world;
};

// Tori (not convex: rays and boxes pass through the hole) at random poses, static.
MeshWorld mesh_world(QueryRng& rng, int bodies, int tree_depth) {
  static const auto shared = [] {
    TriangleMesh torus = tools::make_torus(0.3, 0.1, 32, 12);
    tools::BuildOptions options;
    options.method = tools::BuildMethod::Octree;
    options.depth = 3;
    auto tree = std::make_shared<const SphereTree>(tools::build_sphere_tree(torus, options));
    return std::make_pair(torus, tree);
  }();
  WorldSettings settings;
  settings.collision.tree_depth = tree_depth;
  MeshWorld out{shared.first, shared.second, {}, World(settings)};
  for (int i = 0; i < bodies; ++i) {
    BodyDesc desc;
    desc.tree = out.tree;
    desc.pose.rotation = uniform_rotation(rng);
    desc.pose.translation = uniform_point(rng, 1.2f);
    desc.is_static = true;
    out.world.add_body(desc);
    out.poses.push_back(desc.pose);
  }
  return out;
}

Vec3d placed(const Transform& pose, const Vec3d& body_point) {
  return pose.rotation.cast<double>() * body_point + pose.translation.cast<double>();
}

// Möller–Trumbore in double: where the ray meets the triangle, if it does.
std::optional<double> ray_triangle(const Vec3d& origin, const Vec3d& direction, const Vec3d& a,
                                   const Vec3d& b, const Vec3d& c) {
  const Vec3d e1 = b - a;
  const Vec3d e2 = c - a;
  const Vec3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-14) return std::nullopt;
  const Vec3d s = origin - a;
  const double u = s.dot(p) / det;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Vec3d q = s.cross(e1);
  const double v = direction.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(q) / det;
  if (t < 0.0) return std::nullopt;
  return t;
}

TEST(QueryOnMeshes, RaysHitTheSpheresNoLaterThanTheMesh) {
  for (const int tree_depth : {0, 2}) {
    QueryRng rng(61 + tree_depth);
    const MeshWorld scene = mesh_world(rng, 12, tree_depth);
    const WorldQuery query(scene.world);
    int mesh_hits = 0;
    for (int i = 0; i < 400; ++i) {
      Ray ray;
      ray.origin = uniform_point(rng, 2.5f);
      ray.direction = (uniform_point(rng, 1.0f) - ray.origin).normalized();
      double nearest = std::numeric_limits<double>::infinity();
      std::vector<std::uint32_t> bodies_hit;
      for (std::uint32_t body = 0; body < scene.poses.size(); ++body) {
        bool hit_body = false;
        for (std::size_t t = 0; t < scene.mesh.triangles.size(); ++t) {
          const std::optional<double> hit =
              ray_triangle(ray.origin.cast<double>(), ray.direction.cast<double>(),
                           placed(scene.poses[body], scene.mesh.corner(t, 0)),
                           placed(scene.poses[body], scene.mesh.corner(t, 1)),
                           placed(scene.poses[body], scene.mesh.corner(t, 2)));
          if (hit) {
            nearest = std::min(nearest, *hit);
            hit_body = true;
          }
        }
        if (hit_body) bodies_hit.push_back(body);
      }
      if (bodies_hit.empty()) continue;
      ++mesh_hits;
      const std::optional<RayHit> hit = query.cast_ray(ray);
      ASSERT_TRUE(hit.has_value()) << "ray " << i << " meets a mesh but no sphere";
      EXPECT_LE(hit->distance, nearest + 1e-5);
      std::vector<std::uint32_t> sphere_bodies;
      for (const RayHit& h : query.cast_ray_all(ray)) sphere_bodies.push_back(h.body.index);
      for (const std::uint32_t body : bodies_hit) {
        EXPECT_NE(std::find(sphere_bodies.begin(), sphere_bodies.end(), body), sphere_bodies.end());
      }
    }
    EXPECT_GT(mesh_hits, 100);
  }
}

// Points of the mesh's surface: its vertices and random points of its triangles.
std::vector<Vec3d> surface_samples(QueryRng& rng, const TriangleMesh& mesh) {
  std::vector<Vec3d> out = mesh.vertices;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 4; ++k) {
      double u = unit(rng);
      double v = unit(rng);
      if (u + v > 1.0) {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      out.push_back(mesh.corner(t, 0) + u * (mesh.corner(t, 1) - mesh.corner(t, 0)) +
                    v * (mesh.corner(t, 2) - mesh.corner(t, 0)));
    }
  }
  return out;
}

TEST(QueryOnMeshes, ShapesHoldingSurfacePointsOverlapTheirBodies) {
  QueryRng rng(67);
  const MeshWorld scene = mesh_world(rng, 12, 0);
  const WorldQuery query(scene.world);
  const std::vector<Vec3d> samples = surface_samples(rng, scene.mesh);
  int touching = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 centre = uniform_point(rng, 1.5f);
    const float radius = uniform_in(rng, 0.01f, 0.3f);
    OrientedBox box;
    box.pose.rotation = uniform_rotation(rng);
    box.pose.translation = centre;
    box.half_extents = uniform_point(rng, 0.3f).cwiseAbs();
    const Eigen::Matrix3d box_rotation = box.pose.rotation.cast<double>().toRotationMatrix();
    const auto in = [](const std::vector<BodyId>& ids, std::uint32_t body) {
      return std::any_of(ids.begin(), ids.end(), [&](BodyId id) { return id.index == body; });
    };
    const std::vector<BodyId> by_sphere = query.overlap_sphere(centre, radius);
    const std::vector<BodyId> by_box = query.overlap_box(box);
    for (std::uint32_t body = 0; body < scene.poses.size(); ++body) {
      bool in_sphere = false;
      bool in_box = false;
      for (const Vec3d& sample : samples) {
        const Vec3d p = placed(scene.poses[body], sample);
        in_sphere = in_sphere || (p - centre.cast<double>()).norm() <= radius;
        const Vec3d local = box_rotation.transpose() * (p - centre.cast<double>());
        in_box =
            in_box || (local.cwiseAbs().array() <= box.half_extents.cast<double>().array()).all();
      }
      touching += (in_sphere ? 1 : 0) + (in_box ? 1 : 0);
      if (in_sphere) {
        EXPECT_TRUE(in(by_sphere, body)) << "sphere " << i << " body " << body;
      }
      if (in_box) {
        EXPECT_TRUE(in(by_box, body)) << "box " << i << " body " << body;
      }
    }
  }
  EXPECT_GT(touching, 50);
}

TEST(QueryOnMeshes, LeafGapsAreNeverMoreThanTheMeshDistance) {
  QueryRng rng(71);
  const MeshWorld scene = mesh_world(rng, 10, 0);
  const WorldQuery query(scene.world);
  const tools::MeshQuery mesh_query(scene.mesh);
  const std::vector<Vec3d> samples = surface_samples(rng, scene.mesh);
  int apart = 0;
  for (std::uint32_t a = 0; a < scene.poses.size(); ++a) {
    for (std::uint32_t b = a + 1; b < scene.poses.size(); ++b) {
      const DistanceResult spheres = query.distance(scene.world.id_of(a), scene.world.id_of(b));
      // The meshes are at most this far apart: the nearest of a's surface points to b's mesh.
      const Eigen::Quaterniond to_b = scene.poses[b].rotation.cast<double>().conjugate();
      double mesh_distance = std::numeric_limits<double>::infinity();
      for (const Vec3d& sample : samples) {
        const Vec3d in_b =
            to_b * (placed(scene.poses[a], sample) - scene.poses[b].translation.cast<double>());
        mesh_distance = std::min(mesh_distance, mesh_query.distance(in_b));
      }
      apart += spheres.distance > 0.0f ? 1 : 0;
      EXPECT_LE(spheres.distance, mesh_distance + 1e-5) << "bodies " << a << ", " << b;
    }
  }
  EXPECT_GT(apart, 10);
}

}  // namespace
}  // namespace sphys::test
