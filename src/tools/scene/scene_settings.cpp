#include <algorithm>
#include <cstdint>

#include "sphys/tools/scene.h"

namespace sphys::tools {
namespace {

std::uint32_t count(int value) { return static_cast<std::uint32_t>(std::max(value, 0)); }

}  // namespace

WorldSettings world_settings(const Scene& scene) {
  WorldSettings settings;
  settings.gravity = scene.gravity;
  settings.response = scene.response;
  settings.paper_passes = count(scene.paper_passes);
  settings.collision_passes = count(scene.collision_passes);
  settings.max_collision_passes = count(scene.max_collision_passes);
  settings.collision_pass_travel = scene.collision_pass_travel;
  settings.solver = scene.solver;
  settings.sleep = scene.sleep;
  // The exact plane's material; the octree ground is a body and carries its own.
  settings.ground_restitution = scene.ground.restitution;
  settings.ground_friction = scene.ground.friction;
  return settings;
}

void set_world_settings(Scene& scene, const WorldSettings& settings) {
  scene.gravity = settings.gravity;
  scene.response = settings.response;
  scene.paper_passes = static_cast<int>(settings.paper_passes);
  scene.collision_passes = static_cast<int>(settings.collision_passes);
  scene.max_collision_passes = static_cast<int>(settings.max_collision_passes);
  scene.collision_pass_travel = settings.collision_pass_travel;
  scene.solver = settings.solver;
  scene.sleep = settings.sleep;
  scene.ground.restitution = settings.ground_restitution;
  scene.ground.friction = settings.ground_friction;
}

}  // namespace sphys::tools
