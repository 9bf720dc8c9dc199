#include "support/test_robot_scene.h"

#include <span>

#include "sphys/tools/robot.h"
#include "sphys/tools/spherize.h"
#include "support/test_robot.h"

namespace sphys::test {

std::string scene_with_test_robot(const std::filesystem::path& dir, const std::string& robot_keys,
                                  const std::string& members) {
  const TestRobot written = write_test_robot(dir, standard_test_robot());
  const tools::RobotPackage package = tools::parse_robot_package(written.package_option);
  const tools::Robot robot = tools::load_robot(written.urdf, std::span(&package, 1));
  tools::SpherizeOptions options;
  options.total_spheres = 60;
  tools::write_robot_spheres(dir / "spheres.yml", tools::SphereFileFormat::Curobo, robot,
                             tools::spherize(robot, options));
  return R"({"format": "sphys-scene", "version": 1, "ground": {"type": "plane"},
    "sleep": {"enabled": false}, )" +
         members + R"(,
    "robots": [{"urdf": ")" +
         written.urdf.string() + R"(", "spheres": "spheres.yml",
      "packages": {"test_robot_pkg": ")" +
         written.package_dir.string() + R"("}, "position": [0, 1, 0],
      "orientation": {"axis": [1, 0, 0], "angle_degrees": -90}, )" +
         robot_keys + "}]}";
}

}  // namespace sphys::test
