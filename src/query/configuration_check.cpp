// Batched configuration checks: sphere after sphere against the world's leaf-sphere groups (the
// snapshot's hierarchy, then kLaneWidth leaves at a time), stopping at the first sphere that
// touches; then, if asked, the pairs of spheres of links that may collide. Configurations run in
// runs on the threads.

#include "sphys/configuration_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "query/body_filter.h"
#include "query/group_tests.h"
#include "query/snapshot.h"
#include "sphys/error.h"

namespace sphys {
namespace {

using query_detail::BvhNode;
using query_detail::LeafGroup;
using query_detail::Snapshot;

// Configurations per task on the threads: one is too little work to hand out. unit:
// configurations
constexpr std::size_t kConfigurationsPerRun = 64;

constexpr std::size_t kFloatsPerSphere = 4;  // x, y, z, radius

// The squared distance from a point to a box. unit: m²
float squared_distance(const Aabb& box, float x, float y, float z) {
  const float dx = std::max({box.min.x() - x, x - box.max.x(), 0.0f});
  const float dy = std::max({box.min.y() - y, y - box.max.y(), 0.0f});
  const float dz = std::max({box.min.z() - z, z - box.max.z(), 0.0f});
  return dx * dx + dy * dy + dz * dz;
}

void check_results(std::span<const ConfigurationResult> results, std::size_t configurations) {
  if (results.size() != configurations) {
    throw Error("results: " + std::to_string(results.size()) + " entries for " +
                std::to_string(configurations) + " configurations");
  }
}

}  // namespace

ConfigurationChecker::ConfigurationChecker(const WorldQuery& query,
                                           std::vector<std::int32_t> sphere_links,
                                           ConfigurationCheckSettings settings)
    : query_(&query), links_(std::move(sphere_links)) {
  if (links_.empty()) throw Error("sphere_links: no spheres");
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i] < 0) {
      throw Error("sphere_links[" + std::to_string(i) + "]: negative link " +
                  std::to_string(links_[i]));
    }
    link_count_ = std::max(link_count_, static_cast<std::size_t>(links_[i]) + 1);
  }
  const Snapshot& snapshot = query.snapshot();
  const query_detail::BodyFilter filter(query.world(), snapshot, settings.filter);
  group_seen_.reserve(snapshot.groups.size());
  for (const LeafGroup& group : snapshot.groups) {
    group_seen_.push_back(filter.sees(group.body) ? 1 : 0);
  }
  if (!settings.self_collision) return;
  // Allowed link pairs as a table, either order.
  std::vector<std::uint8_t> allowed(link_count_ * link_count_, 0);
  for (const auto& [a, b] : settings.allowed_link_pairs) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= link_count_ ||
        static_cast<std::size_t>(b) >= link_count_) {
      throw Error("allowed_link_pairs: (" + std::to_string(a) + ", " + std::to_string(b) +
                  ") names a link no sphere has (links 0.." + std::to_string(link_count_ - 1) +
                  ")");
    }
    allowed[a * link_count_ + b] = 1;
    allowed[b * link_count_ + a] = 1;
  }
  for (std::size_t i = 0; i < links_.size(); ++i) {
    for (std::size_t j = i + 1; j < links_.size(); ++j) {
      if (links_[i] != links_[j] && allowed[links_[i] * link_count_ + links_[j]] == 0) {
        self_pairs_.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
      }
    }
  }
}

std::int32_t ConfigurationChecker::touched_body(float x, float y, float z, float radius) const {
  const Snapshot& snapshot = query_->snapshot();
  if (snapshot.bvh.empty()) return -1;
  const float radius_squared = radius * radius;
  const Vec3 centre(x, y, z);
  std::array<std::uint32_t, query_detail::kMaxBvhDepth> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& node = snapshot.bvh[stack[--top]];
    if (squared_distance(node.bounds, x, y, z) > radius_squared) continue;
    if (node.count == 0) {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
      continue;
    }
    for (std::uint32_t g = node.first; g < node.first + node.count; ++g) {
      const LeafGroup& group = snapshot.groups[g];
      if (group_seen_[g] != 0 && squared_distance(group.bounds, x, y, z) <= radius_squared &&
          query_detail::group_touches_sphere(snapshot, group, centre, radius)) {
        return static_cast<std::int32_t>(group.body);
      }
    }
  }
  return -1;
}

ConfigurationResult ConfigurationChecker::check_one(const float* spheres) const {
  ConfigurationResult result;
  const auto collide = [&](std::size_t sphere, std::int32_t body, std::int32_t other) {
    result.free = false;
    result.sphere = static_cast<std::int32_t>(sphere);
    result.body = body;
    result.other_sphere = other;
    return result;
  };
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const float* s = spheres + i * kFloatsPerSphere;
    // A sum of the four is finite only when each is: a NaN or infinite sphere is never free.
    if (!std::isfinite(s[0] + s[1] + s[2] + s[3]) || s[3] < 0.0f) return collide(i, -1, -1);
    const std::int32_t body = touched_body(s[0], s[1], s[2], s[3]);
    if (body >= 0) return collide(i, body, -1);
  }
  for (const auto& [i, j] : self_pairs_) {
    const float* a = spheres + i * kFloatsPerSphere;
    const float* b = spheres + j * kFloatsPerSphere;
    const float dx = a[0] - b[0];
    const float dy = a[1] - b[1];
    const float dz = a[2] - b[2];
    const float reach = a[3] + b[3];
    if (dx * dx + dy * dy + dz * dz <= reach * reach) return collide(i, -1, j);
  }
  return result;
}

void ConfigurationChecker::check(std::span<const float> spheres,
                                 std::span<ConfigurationResult> results,
                                 const Parallel* parallel) const {
  const std::size_t per_configuration = links_.size() * kFloatsPerSphere;
  if (spheres.size() % per_configuration != 0) {
    throw Error("spheres: " + std::to_string(spheres.size()) +
                " floats is no whole number of configurations of " + std::to_string(links_.size()) +
                " spheres × 4 (x, y, z, radius)");
  }
  const std::size_t count = spheres.size() / per_configuration;
  check_results(results, count);
  for_each_on(parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun,
              [&](std::size_t run) {
                const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
                for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) {
                  results[c] = check_one(spheres.data() + c * per_configuration);
                }
              });
}

void ConfigurationChecker::check_link_poses(std::span<const Transform> link_poses,
                                            std::span<const Sphere> link_spheres,
                                            std::span<ConfigurationResult> results,
                                            const Parallel* parallel) const {
  if (link_spheres.size() != links_.size()) {
    throw Error("link_spheres: " + std::to_string(link_spheres.size()) + " spheres for " +
                std::to_string(links_.size()) + " sphere links");
  }
  if (link_poses.size() % link_count_ != 0) {
    throw Error("link_poses: " + std::to_string(link_poses.size()) +
                " poses is no whole number of configurations of " + std::to_string(link_count_) +
                " links");
  }
  const std::size_t count = link_poses.size() / link_count_;
  check_results(results, count);
  for_each_on(
      parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun, [&](std::size_t run) {
        std::vector<Mat3> rotations(link_count_);
        std::vector<float> posed(links_.size() * kFloatsPerSphere);
        const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
        for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) {
          const Transform* poses = link_poses.data() + c * link_count_;
          for (std::size_t l = 0; l < link_count_; ++l) {
            rotations[l] = poses[l].rotation.toRotationMatrix();
          }
          for (std::size_t i = 0; i < links_.size(); ++i) {
            const Transform& pose = poses[links_[i]];
            const Vec3 centre = rotations[links_[i]] * link_spheres[i].center + pose.translation;
            float* out = posed.data() + i * kFloatsPerSphere;
            out[0] = centre.x();
            out[1] = centre.y();
            out[2] = centre.z();
            out[3] = link_spheres[i].radius;
          }
          results[c] = check_one(posed.data());
        }
      });
}

}  // namespace sphys
