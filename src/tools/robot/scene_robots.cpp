#include "sphys/tools/scene_robots.h"

#include <string>

#include "sphys/error.h"
#include "sphys/tools/robot_model_file.h"

namespace sphys::tools {

std::vector<RobotId> add_scene_robots(const Scene& scene, World& world) {
  std::vector<RobotId> ids;
  for (std::size_t k = 0; k < scene.robots.size(); ++k) {
    const SceneRobot& robot = scene.robots[k];
    const std::string where = scene.name + ": /robots/" + std::to_string(k) + ": ";
    try {
      const auto from_scene = [&](const std::filesystem::path& path) {
        return scene.base_directory / path;
      };
      std::vector<RobotPackage> packages;
      for (const auto& [name, folder] : robot.packages) {
        packages.push_back({name, from_scene(folder)});
      }
      const RobotModel model =
          load_robot_model(from_scene(robot.urdf), from_scene(robot.spheres), packages,
                           robot.srdf ? std::optional(from_scene(*robot.srdf)) : std::nullopt);
      const RobotId id = world.add_robot(model, {robot.orientation, robot.position},
                                         robot.fixed_base ? RobotBase::kFixed : RobotBase::kFree);
      if (!robot.configuration.empty()) world.set_robot_configuration(id, robot.configuration);
      if (!robot.targets.empty()) {
        if (robot.targets.size() != model.joints.size()) {
          throw Error("targets: " + std::to_string(robot.targets.size()) + " values for " +
                      std::to_string(model.joints.size()) + " joints");
        }
        check_joint_values(model, robot.targets, "targets");
        std::vector<RobotJointControl> controls(model.joints.size());
        for (std::size_t j = 0; j < controls.size(); ++j) {
          controls[j].mode = RobotControlMode::kPosition;
          controls[j].target_position = robot.targets[j];
        }
        world.set_robot_controls(id, controls);
      }
      ids.push_back(id);
    } catch (const Error& error) {
      throw Error(where + error.what());
    }
  }
  return ids;
}

}  // namespace sphys::tools
