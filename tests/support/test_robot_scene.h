#pragma once

// A scene file's text with the test robot (support/test_robot.h) in it, for the tests of robots
// in scenes: the world's, the command line's and the viewer's.

#include <filesystem>
#include <string>

namespace sphys::test {

// The test robot's URDF and 60 spheres written into `dir`, and a scene (exact ground plane, no
// sleep) standing it upright 1 m up with `robot_keys` added to its entry, and `members` (JSON
// object members: its bodies, its time step, ...).
[[nodiscard]] std::string scene_with_test_robot(const std::filesystem::path& dir,
                                                const std::string& robot_keys,
                                                const std::string& members = R"("bodies": [])");

}  // namespace sphys::test
