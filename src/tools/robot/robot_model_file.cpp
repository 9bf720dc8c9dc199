// A robot's files compiled into the runtime's RobotModel: the URDF's tree of links and joints,
// the spheres on its links and the SRDF's pairs of links that are never checked.

#include "sphys/tools/robot_model_file.h"

#include <algorithm>
#include <optional>
#include <string>
#include <tinyxml2.h>

#include "io/input_file.h"
#include "robot_chain.h"
#include "sphys/error.h"
#include "sphys/tools/mass_properties.h"

namespace sphys::tools {
namespace {

RobotJointType joint_type(const Robot& robot, const RobotJoint& joint) {
  if (!joint.mimics.empty()) {
    throw Error::in_file(robot.file, "joint \"" + joint.name + "\" mimics \"" + joint.mimics +
                                         "\": mimic joints are not supported by robot checks");
  }
  if (const std::optional<RobotJointType> type = urdf_joint_motion(joint)) return *type;
  throw Error::in_file(robot.file, "joint \"" + joint.name + "\" is " + joint.type +
                                       ": robot checks take revolute, continuous, prismatic and "
                                       "fixed joints");
}

// A link's mass, centre and inertia: its <inertial>'s, or else its geometry's at the default
// density (flagged), or none.
void give_mass(const Robot& robot, RobotModel::Link& link) {
  if (const auto inertial = robot.inertials.find(link.name); inertial != robot.inertials.end()) {
    link.mass = inertial->second.mass;
    link.center_of_mass = inertial->second.center_of_mass;
    link.inertia = inertial->second.inertia;
    return;
  }
  const auto geometry = std::ranges::find(robot.links, link.name, &LinkGeometry::link);
  if (geometry == robot.links.end()) return;
  MassPropertiesOptions options;
  options.density = kDefaultLinkDensity;
  const MassProperties mass = compute_mass_properties(geometry->mesh, options);
  link.mass = mass.mass;
  link.center_of_mass = mass.center_of_mass;
  link.inertia = mass.inertia;
  link.mass_from_geometry = true;
}

}  // namespace

RobotModel robot_model(const Robot& robot, std::span<const LinkSpheres> links,
                       std::span<const std::array<std::string, 2>> disabled) {
  RobotModel model = robot_chain(robot, [&](const RobotJoint& joint) {
    return joint.type == "fixed" ? std::nullopt : std::optional(joint_type(robot, joint));
  });
  for (RobotModel::Link& link : model.links) give_mass(robot, link);
  for (const LinkSpheres& link : links) {
    std::int32_t index = -1;
    try {
      index = model.link_index(link.link);
    } catch (const Error&) {
      throw Error::in_file(robot.file, "has no link \"" + link.link + "\" for its spheres");
    }
    for (const Sphere& sphere : link.spheres) {
      model.sphere_links.push_back(index);
      model.spheres.push_back(sphere);
    }
  }
  for (const auto& [a, b] : disabled) {
    // Pairs naming links the robot does not have (an SRDF for another version of it) are left
    // out: they disable nothing.
    const auto has = [&](const std::string& n) {
      return std::ranges::any_of(model.links,
                                 [&](const RobotModel::Link& l) { return l.name == n; });
    };
    if (has(a) && has(b))
      model.allowed_link_pairs.push_back({model.link_index(a), model.link_index(b)});
  }
  check_robot_model(model);
  return model;
}

std::vector<std::array<std::string, 2>> read_disabled_collisions(
    const std::filesystem::path& srdf) {
  const std::string text = read_input_file(srdf, InputKind::kRobot);
  tinyxml2::XMLDocument document;
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw Error::at_line(srdf, static_cast<std::size_t>(std::max(document.ErrorLineNum(), 1)),
                         std::string("not valid XML: ") + document.ErrorStr());
  }
  const tinyxml2::XMLElement* root = document.RootElement();
  if (root == nullptr || std::string(root->Name()) != "robot") {
    throw Error::in_file(srdf, "is not an SRDF (its root element is not <robot>)");
  }
  std::vector<std::array<std::string, 2>> pairs;
  for (const tinyxml2::XMLElement* element = root->FirstChildElement("disable_collisions");
       element != nullptr; element = element->NextSiblingElement("disable_collisions")) {
    const char* a = element->Attribute("link1");
    const char* b = element->Attribute("link2");
    if (a == nullptr || b == nullptr) {
      throw Error::at_line(srdf, static_cast<std::size_t>(element->GetLineNum()),
                           "disable_collisions needs both link1 and link2");
    }
    pairs.push_back({a, b});
  }
  return pairs;
}

LoadedRobot load_robot_files(const std::filesystem::path& urdf,
                             const std::filesystem::path& spheres,
                             std::span<const RobotPackage> packages,
                             const std::optional<std::filesystem::path>& srdf) {
  LoadedRobot loaded;
  loaded.robot = load_robot(urdf, packages);
  const std::vector<LinkSpheres> links = read_robot_spheres(spheres);
  const std::vector<std::array<std::string, 2>> disabled =
      srdf ? read_disabled_collisions(*srdf) : std::vector<std::array<std::string, 2>>{};
  loaded.model = robot_model(loaded.robot, links, disabled);
  return loaded;
}

RobotModel load_robot_model(const std::filesystem::path& urdf, const std::filesystem::path& spheres,
                            std::span<const RobotPackage> packages,
                            const std::optional<std::filesystem::path>& srdf) {
  return load_robot_files(urdf, spheres, packages, srdf).model;
}

}  // namespace sphys::tools
