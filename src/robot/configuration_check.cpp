// Batched configuration checks. Per configuration, each link's spheres are bounded by one box
// (link_boxes.cpp), and one walk of the snapshot's hierarchy (or, inside a known reach, a scan of
// the groups within it), the links' boxes in lanes, collects the groups near each link
// (near_groups.cpp); then the spheres of the links near any are tested against their link's groups
// and, if asked, each other (configuration_answer.cpp). Configurations run in runs on the threads.

#include "sphys/configuration_check.h"

#include <algorithm>
#include <string>
#include <vector>

#include "robot/configuration_layout.h"
#include "robot/configuration_scratch.h"
#include "sphys/error.h"

namespace sphys {
namespace {

void check_results(std::span<const ConfigurationResult> results, std::size_t configurations) {
  if (results.size() != configurations) {
    throw Error("results: " + std::to_string(results.size()) + " entries for " +
                std::to_string(configurations) + " configurations");
  }
}

}  // namespace

ConfigurationResult ConfigurationChecker::check_one(const float* spheres, Scratch& scratch) const {
  scratch.bound_links(spheres, links_);
  collect_candidates(scratch);
  return answer(spheres, scratch, true);
}

template <class Check>
void ConfigurationChecker::run_configurations(std::size_t count, const Parallel* parallel,
                                              const Check& check) const {
  for_each_on(parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun,
              [&](std::size_t run) {
                Scratch scratch(links_, link_count_);
                const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
                for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) check(c, scratch);
              });
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
  run_configurations(count, parallel, [&](std::size_t c, Scratch& scratch) {
    results[c] = check_one(spheres.data() + c * per_configuration, scratch);
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
  // Each run poses its configurations in its own buffer.
  for_each_on(
      parallel, (count + kConfigurationsPerRun - 1) / kConfigurationsPerRun, [&](std::size_t run) {
        Scratch scratch(links_, link_count_);
        std::vector<Mat3> rotations(link_count_);
        std::vector<float> posed_run(links_.size() * kFloatsPerSphere);
        const std::size_t end = std::min(count, (run + 1) * kConfigurationsPerRun);
        for (std::size_t c = run * kConfigurationsPerRun; c < end; ++c) {
          const Transform* poses = link_poses.data() + c * link_count_;
          for (std::size_t l = 0; l < link_count_; ++l) {
            rotations[l] = poses[l].rotation.toRotationMatrix();
          }
          for (std::size_t i = 0; i < links_.size(); ++i) {
            const auto link = static_cast<std::size_t>(links_[i]);
            const Vec3 centre = rotations[link] * link_spheres[i].center + poses[link].translation;
            float* out = posed_run.data() + i * kFloatsPerSphere;
            out[0] = centre.x();
            out[1] = centre.y();
            out[2] = centre.z();
            out[3] = link_spheres[i].radius;
          }
          results[c] = check_one(posed_run.data(), scratch);
        }
      });
}

}  // namespace sphys
