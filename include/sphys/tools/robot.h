#pragma once

// A robot described by a URDF file, as `sphys spherize` and `sphys view` need it: each link's
// geometry as one triangle mesh in the link's frame, and the joints that place the links.

#include <filesystem>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools {

using Pose3d = Eigen::Isometry3d;  // a rigid pose in double. unit: m

// Where `package://NAME/...` mesh paths of the URDF point: NAME's directory.
struct RobotPackage {
  std::string name;                 // NAME in package://NAME/...
  std::filesystem::path directory;  // where NAME's files are
};

// Reads "NAME=DIR" (the --package option); throws sphys::Error when either side is empty.
[[nodiscard]] RobotPackage parse_robot_package(std::string_view text);

// One link's geometry: every collision element merged into one mesh in the link's frame (the
// elements' origins and mesh scales applied), or every visual element when the link has no
// collision element.
struct LinkGeometry {
  std::string link;          // the link's name
  TriangleMesh mesh;         // unit: m
  bool from_visual = false;  // the link had no collision element: its visual ones were taken
  // Boxes and meshes are exact; cylinders and spheres are meshed with their vertices on the true
  // surface, which then lies at most this far outside the mesh. Spheres covering the mesh cover
  // the true shape once grown by this much. unit: m
  double tessellation_error = 0.0;
  // One entry per element, for reports: the mesh file as resolved, or "box", "cylinder", "sphere".
  std::vector<std::string> sources;
};

// A joint of the URDF, as it declares it.
struct RobotJoint {
  std::string name;                    // the joint's name
  std::string type;                    // revolute, continuous, prismatic, fixed, floating or planar
  std::string parent;                  // the parent link's name
  std::string child;                   // the child link's name, the link the joint moves
  Pose3d origin = Pose3d::Identity();  // the child's frame in the parent's at joint value 0
  Vec3d axis = Vec3d::UnitX();         // unit vector in the child's frame
  // The limits of a revolute or prismatic joint (rad, m); infinite for a continuous one.
  double lower = 0.0;
  double upper = 0.0;  // unit: rad or m
  std::string mimics;  // the joint it mimics, or empty
  // The URDF's `limit` element's effort and velocity; infinite where it gives none (or 0).
  double effort = std::numeric_limits<double>::infinity();    // unit: N·m or N
  double velocity = std::numeric_limits<double>::infinity();  // unit: rad/s or m/s
};

// A link's `inertial` element.
struct LinkInertial {
  double mass = 0.0;                     // unit: kg
  Vec3d center_of_mass = Vec3d::Zero();  // in the link's frame. unit: m
  Mat3d inertia = Mat3d::Zero();         // about the centre of mass, the link's axes. unit: kg·m²
};

// A robot as load_robot reads it from its URDF.
struct Robot {
  std::string name;                      // the URDF's robot name
  std::filesystem::path file;            // the URDF read
  std::string root_link;                 // the link that is no joint's child
  std::vector<LinkGeometry> links;       // the links that have geometry, by name
  std::vector<std::string> empty_links;  // links with neither collision nor visual geometry
  std::vector<RobotJoint> joints;        // every joint of the URDF, by name
  std::map<std::string, LinkInertial>
      inertials;  // the links that have an `inertial` element, by name
};

// Reads the URDF, resolving mesh files given as `package://NAME/...` (through `packages`), as
// `file://` URIs, or relative to the URDF's folder. Throws sphys::Error naming the file (and the
// link and mesh file when one is at fault) for a missing or malformed URDF, a missing or corrupt
// mesh, an unknown package, a non-finite or non-positive scale or size, or a robot without any
// geometry.
[[nodiscard]] Robot load_robot(const std::filesystem::path& urdf,
                               std::span<const RobotPackage> packages = {});

// Every link's pose in the root link's frame for the given joint values (rad for revolute and
// continuous joints, m for prismatic ones; a joint not named stands at 0). Throws sphys::Error
// naming a joint that the robot does not have, or one that is fixed, floating or planar.
[[nodiscard]] std::map<std::string, Pose3d> link_poses(
    const Robot& robot, const std::map<std::string, double>& joint_values = {});

}  // namespace sphys::tools
