// URDF files through urdfdom: each link's collision (or visual) elements merged into one mesh in
// the link's frame, and the joints.
#include <cmath>
#include <console_bridge/console.h>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <urdf_parser/urdf_parser.h>
#include <utility>
#include <vector>

#include "io/input_file.h"
#include "sphys/error.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/robot.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Cylinders and spheres are meshed finely enough that the true surface is within 0.5% of the
// radius of the mesh (1 - cos(π/64) = 0.0012; the faces of the icosphere's 1,280 come within
// 0.5%), and coarsely enough that the link's spheres take a fraction of a second.
constexpr int kCylinderSides = 64;
constexpr int kSphereSubdivisions = 3;

// urdfdom tells why a file is not a URDF through console_bridge, on standard error by default.
// While a file is parsed the messages are collected instead, to go into sphys's one-line error.
class CollectMessages final : public console_bridge::OutputHandler {
 public:
  CollectMessages() { console_bridge::useOutputHandler(this); }
  ~CollectMessages() override { console_bridge::restorePreviousOutputHandler(); }
  CollectMessages(const CollectMessages&) = delete;
  CollectMessages& operator=(const CollectMessages&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error_.empty()) {
      first_error_ = text;
    }
  }
  [[nodiscard]] const std::string& first_error() const { return first_error_; }

 private:
  std::string first_error_;
};

Pose3d to_pose(const urdf::Pose& pose) {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  pose.rotation.getQuaternion(x, y, z, w);
  Pose3d result = Pose3d::Identity();
  result.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  result.translation() = Vec3d(pose.position.x, pose.position.y, pose.position.z);
  return result;
}

Vec3d to_vec(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// Where a link's problem is: "<urdf>: link "<name>": <problem>".
Error link_error(const fs::path& urdf, const std::string& link, const std::string& problem) {
  return Error::in_file(urdf, "link \"" + link + "\": " + problem);
}

fs::path resolve_mesh_path(const fs::path& urdf, const std::string& link,
                           const std::string& filename, std::span<const RobotPackage> packages) {
  constexpr std::string_view kPackage = "package://";
  constexpr std::string_view kFile = "file://";
  if (filename.starts_with(kPackage)) {
    const std::string rest = filename.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash);
    for (const RobotPackage& package : packages) {
      if (package.name == name) {
        return slash == std::string::npos ? package.directory
                                          : package.directory / rest.substr(slash + 1);
      }
    }
    throw link_error(urdf, link,
                     "mesh \"" + filename + "\" is in package \"" + name +
                         "\", which no --package " + name + "=DIR locates");
  }
  fs::path path =
      filename.starts_with(kFile) ? fs::path(filename.substr(kFile.size())) : fs::path(filename);
  if (path.empty()) throw link_error(urdf, link, "a mesh element has no file name");
  return path.is_absolute() ? path : urdf.parent_path() / path;
}

bool positive_finite(double value) { return std::isfinite(value) && value > 0.0; }

// Farthest the true sphere lies outside its icosphere: the radius less the nearest face plane.
double icosphere_gap(const TriangleMesh& mesh, double radius) {
  double nearest = radius;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    nearest = std::min(nearest, mesh.corner(t, 0).dot(mesh.area_normal(t).normalized()));
  }
  return radius - nearest;
}

// One element's geometry as a mesh in its own frame, with the gap between it and the true shape.
struct ElementMesh {
  TriangleMesh mesh;
  double tessellation_error = 0.0;
  std::string source;
};

ElementMesh element_mesh(const fs::path& urdf, const std::string& link,
                         const urdf::Geometry& geometry, std::span<const RobotPackage> packages) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const Vec3d size = to_vec(static_cast<const urdf::Box&>(geometry).dim);
      if (!positive_finite(size.x()) || !positive_finite(size.y()) || !positive_finite(size.z())) {
        throw link_error(urdf, link, "a box's size must be positive and finite");
      }
      return {make_box(size), 0.0, "box"};
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
      if (!positive_finite(cylinder.radius) || !positive_finite(cylinder.length)) {
        throw link_error(urdf, link, "a cylinder's radius and length must be positive and finite");
      }
      return {make_cylinder(cylinder.radius, cylinder.length, kCylinderSides),
              cylinder.radius * (1.0 - std::cos(std::numbers::pi / kCylinderSides)), "cylinder"};
    }
    case urdf::Geometry::SPHERE: {
      const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
      if (!positive_finite(radius)) {
        throw link_error(urdf, link, "a sphere's radius must be positive and finite");
      }
      TriangleMesh mesh = make_icosphere(radius, kSphereSubdivisions);
      const double gap = icosphere_gap(mesh, radius);
      return {std::move(mesh), gap, "sphere"};
    }
    case urdf::Geometry::MESH: {
      const auto& element = static_cast<const urdf::Mesh&>(geometry);
      const Vec3d scale = to_vec(element.scale);
      if (!scale.allFinite() || (scale.array() == 0.0).any()) {
        throw link_error(urdf, link,
                         "mesh \"" + element.filename + "\" has a zero or non-finite scale");
      }
      const fs::path path = resolve_mesh_path(urdf, link, element.filename, packages);
      TriangleMesh mesh;
      try {
        mesh = load_mesh(path);
      } catch (const Error& error) {
        throw link_error(urdf, link, error.what());
      }
      for (Vec3d& v : mesh.vertices) v = v.cwiseProduct(scale);
      // A mirroring scale turns the triangles inside out; turn them back.
      if (scale.prod() < 0.0) {
        for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
      }
      return {std::move(mesh), 0.0, path.string()};
    }
  }
  throw link_error(urdf, link, "a geometry of unknown type");
}

template <typename Element>
LinkGeometry merge_elements(const fs::path& urdf, const std::string& link,
                            const std::vector<std::shared_ptr<Element>>& elements,
                            std::span<const RobotPackage> packages) {
  LinkGeometry geometry;
  geometry.link = link;
  geometry.mesh.name = urdf.string() + " link \"" + link + "\"";
  for (const std::shared_ptr<Element>& element : elements) {
    if (!element || !element->geometry) continue;
    ElementMesh part = element_mesh(urdf, link, *element->geometry, packages);
    const Pose3d origin = to_pose(element->origin);
    const auto offset = static_cast<std::uint32_t>(geometry.mesh.vertices.size());
    for (const Vec3d& v : part.mesh.vertices) geometry.mesh.vertices.push_back(origin * v);
    for (const Triangle& t : part.mesh.triangles) {
      geometry.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
    geometry.tessellation_error = std::max(geometry.tessellation_error, part.tessellation_error);
    geometry.sources.push_back(std::move(part.source));
  }
  return geometry;
}

std::string joint_type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

// A link's <inertial>, its inertia turned from the element's origin into the link's axes.
LinkInertial link_inertial(const fs::path& urdf, const std::string& link,
                           const urdf::Inertial& element) {
  LinkInertial inertial;
  inertial.mass = element.mass;
  const Pose3d origin = to_pose(element.origin);
  inertial.center_of_mass = origin.translation();
  Mat3d inertia;
  inertia << element.ixx, element.ixy, element.ixz, element.ixy, element.iyy, element.iyz,
      element.ixz, element.iyz, element.izz;
  inertial.inertia = origin.linear() * inertia * origin.linear().transpose();
  if (!std::isfinite(inertial.mass) || inertial.mass < 0.0 || !inertial.inertia.allFinite()) {
    throw link_error(urdf, link, "its <inertial> mass must be finite and not negative");
  }
  return inertial;
}

}  // namespace

RobotPackage parse_robot_package(std::string_view text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string_view::npos || equals == 0 || equals + 1 == text.size()) {
    throw Error("--package: expected NAME=DIR, got \"" + std::string(text) + "\"");
  }
  return {std::string(text.substr(0, equals)), fs::path(text.substr(equals + 1))};
}

Robot load_robot(const fs::path& urdf, std::span<const RobotPackage> packages) {
  const std::string text = read_input_file(urdf, InputKind::kRobot);
  urdf::ModelInterfaceSharedPtr model;
  {
    const CollectMessages messages;
    model = urdf::parseURDF(text);
    if (!model) {
      throw Error::in_file(urdf, "not a valid URDF: " + (messages.first_error().empty()
                                                             ? std::string("urdfdom refused it")
                                                             : messages.first_error()));
    }
  }
  Robot robot;
  robot.name = model->getName();
  robot.file = urdf;
  if (model->getRoot()) robot.root_link = model->getRoot()->name;
  for (const auto& [name, link] : model->links_) {
    LinkGeometry geometry = merge_elements(urdf, name, link->collision_array, packages);
    if (geometry.mesh.triangles.empty()) {
      geometry = merge_elements(urdf, name, link->visual_array, packages);
      geometry.from_visual = true;
    }
    if (link->inertial) robot.inertials[name] = link_inertial(urdf, name, *link->inertial);
    if (geometry.mesh.triangles.empty()) {
      robot.empty_links.push_back(name);
    } else {
      robot.links.push_back(std::move(geometry));
    }
  }
  if (robot.links.empty()) {
    throw Error::in_file(urdf, "no link has collision or visual geometry");
  }
  for (const auto& [name, joint] : model->joints_) {
    RobotJoint j;
    j.name = name;
    j.type = joint_type_name(joint->type);
    j.parent = joint->parent_link_name;
    j.child = joint->child_link_name;
    j.origin = to_pose(joint->parent_to_joint_origin_transform);
    const Vec3d axis = to_vec(joint->axis);
    if (axis.norm() > 0.0) j.axis = axis.normalized();
    if (joint->type == urdf::Joint::CONTINUOUS) {
      j.lower = -std::numeric_limits<double>::infinity();
      j.upper = std::numeric_limits<double>::infinity();
    } else if (joint->limits) {
      j.lower = joint->limits->lower;
      j.upper = joint->limits->upper;
    }
    if (joint->limits) {
      // urdfdom reads a missing effort or velocity as 0: no bound.
      if (joint->limits->effort > 0.0) j.effort = joint->limits->effort;
      if (joint->limits->velocity > 0.0) j.velocity = joint->limits->velocity;
    }
    if (joint->mimic) j.mimics = joint->mimic->joint_name;
    robot.joints.push_back(std::move(j));
  }
  return robot;
}

}  // namespace sphys::tools
