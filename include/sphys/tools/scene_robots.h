#pragma once

// A scene's robots (Scene::robots) added to the world build_world made of it: each loaded from its
// files, put where the scene says and, with targets, held there by position control.

#include <vector>

#include "sphys/tools/scene.h"
#include "sphys/world.h"

namespace sphys::tools {

// Adds the scene's robots to `world`, in order, and returns their ids. Throws sphys::Error naming
// the robot ("<scene>: /robots/<k>: ...") for a file that does not load, or a configuration or
// targets that are not one value per joint within its limits.
std::vector<RobotId> add_scene_robots(const Scene& scene, World& world);

}  // namespace sphys::tools
