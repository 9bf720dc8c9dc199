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
  settings.substeps = count(scene.substeps);
  settings.max_substeps = count(scene.max_substeps);
  settings.substep_travel = scene.substep_travel;
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
  scene.substeps = static_cast<int>(settings.substeps);
  scene.max_substeps = static_cast<int>(settings.max_substeps);
  scene.substep_travel = settings.substep_travel;
  scene.solver = settings.solver;
  scene.sleep = settings.sleep;
  scene.ground.restitution = settings.ground_restitution;
  scene.ground.friction = settings.ground_friction;
}

}  // namespace sphys::tools
