#pragma once

// A small robot for the tests of `sphys spherize`: its URDF and mesh files written by the test
// itself, and the ground truth of each link's geometry sampled independently of sphys (meshes from
// their triangles, boxes from their faces, cylinders and spheres from their equations, never from
// a tessellation).

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sphys::test {

// A triangle mesh as it goes into a file, in the file's units. Every coordinate is a float, so
// that STL (single precision), ASCII STL and OBJ readers all read the same numbers.
struct RobotMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// Closed meshes centred on the origin, counter-clockwise seen from outside.
[[nodiscard]] RobotMesh box_mesh(const Eigen::Vector3d& size);
// A torus around the z axis: a ring of radius `ring_radius` of tubes of radius `tube_radius`.
[[nodiscard]] RobotMesh torus_mesh(double ring_radius, double tube_radius, int ring_segments,
                                   int tube_segments);
// A capsule along the z axis: a cylinder `2 half_length` long between two hemispheres.
[[nodiscard]] RobotMesh capsule_mesh(double radius, double half_length, int segments,
                                     int rings_per_cap);
// Every coordinate times `factor` (rounded to float again): a mesh in other units.
[[nodiscard]] RobotMesh scaled_mesh(const RobotMesh& mesh, double factor);

enum class MeshFileType { BinaryStl, AsciiStl, Obj };
// How the URDF names a mesh file: `meshes/NAME` beside the URDF, `package://test_robot_pkg/
// meshes/NAME` in the package folder, or `file://` and its absolute path beside the URDF.
enum class MeshReference { Relative, Package, FileUri };

// One <collision> or <visual> element.
struct RobotGeometry {
  enum class Kind { Box, Cylinder, Sphere, Mesh };
  Kind kind = Kind::Box;
  Eigen::Vector3d size = Eigen::Vector3d::Ones();  // box edge lengths. unit: m
  double radius = 0.0;                             // cylinder and sphere. unit: m
  double length = 0.0;                             // cylinder, along its z axis. unit: m
  RobotMesh mesh;                                  // in the file's units
  std::string file_name;                           // e.g. "upper_arm.stl"
  MeshFileType file_type = MeshFileType::BinaryStl;
  MeshReference reference = MeshReference::Relative;
  std::optional<Eigen::Vector3d> scale;           // the mesh's scale attribute; none: not written
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // <origin xyz>. unit: m
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();  // <origin rpy>. unit: rad
};

[[nodiscard]] RobotGeometry box_geometry(const Eigen::Vector3d& size, const Eigen::Vector3d& xyz,
                                         const Eigen::Vector3d& rpy = Eigen::Vector3d::Zero());
[[nodiscard]] RobotGeometry cylinder_geometry(double radius, double length,
                                              const Eigen::Vector3d& xyz,
                                              const Eigen::Vector3d& rpy = Eigen::Vector3d::Zero());
[[nodiscard]] RobotGeometry sphere_geometry(double radius, const Eigen::Vector3d& xyz);
[[nodiscard]] RobotGeometry mesh_geometry(RobotMesh mesh, std::string file_name, MeshFileType type,
                                          MeshReference reference, const Eigen::Vector3d& xyz,
                                          const Eigen::Vector3d& rpy = Eigen::Vector3d::Zero(),
                                          std::optional<Eigen::Vector3d> scale = std::nullopt);

struct RobotLinkSpec {
  std::string name;
  std::vector<RobotGeometry> collisions;
  std::vector<RobotGeometry> visuals;
};

struct RobotJointSpec {
  std::string name;
  std::string type;  // revolute, prismatic or fixed
  std::string parent;
  std::string child;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // unit: m
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();  // unit: rad
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double lower = 0.0;  // limits of revolute (rad) and prismatic (m) joints
  double upper = 0.0;
};

struct RobotSpec {
  std::string name;
  std::vector<RobotLinkSpec> links;
  std::vector<RobotJointSpec> joints;
};

// The package name the robot's `package://` meshes use.
inline constexpr const char* kTestRobotPackage = "test_robot_pkg";

// Eight links, seven with geometry: base_link (collision box; a visual cylinder that must be
// ignored), shoulder_link (collision cylinder and box), upper_arm_link (a torus in binary STL with
// origin, rotation and a non-uniform scale), forearm_link (a capsule in OBJ, from the package),
// hand_link (visual only: an ASCII STL box named by a file:// URI and a sphere), finger_left_link
// (a 2 mm × 20 mm × 50 mm plate in binary STL), finger_right_link (the same plate in OBJ written
// in millimetres, scale 0.001, turned half a turn), and tool0 without geometry. Revolute,
// prismatic and fixed joints.
[[nodiscard]] RobotSpec standard_test_robot();

// What one link's geometry truly is, in the link's frame (the URDF's origins and scales applied).
struct LinkTruth {
  // Points on the true surface: every mesh vertex, points along every edge, every triangle's
  // centroid and area-weighted random points; box corners, edges and faces; cylinder rims, sides
  // and caps and sphere points from their equations. unit: m
  std::vector<Eigen::Vector3d> samples;
  Eigen::AlignedBox3d bounds;     // exact bounds of the true geometry. unit: m
  bool from_visual = false;       // the link has no collision element: its visuals count
  bool curved_primitive = false;  // a cylinder or sphere element (meshed by the command)
  // One per element: "box", "cylinder", "sphere" or the mesh file's name.
  std::vector<std::string> sources;
};

struct TestRobot {
  std::string name;
  std::filesystem::path urdf;
  std::filesystem::path package_dir;
  std::string package_option;                    // "test_robot_pkg=DIR", for --package
  std::vector<std::string> links;                // every link, in the file's order
  std::vector<std::string> links_with_geometry;  // in the file's order
  std::map<std::string, LinkTruth> truth;        // the links with geometry
};

// Writes the URDF as `dir/robot/NAME.urdf`, its meshes in `dir/robot/meshes/` and the package's
// in `dir/test_robot_pkg/meshes/`, and samples the ground truth (with a fixed seed).
[[nodiscard]] TestRobot write_test_robot(const std::filesystem::path& dir, const RobotSpec& spec);

// The URDF text of a robot whose meshes lie where write_test_robot puts them.
[[nodiscard]] std::string test_robot_urdf(const std::filesystem::path& dir, const RobotSpec& spec);

}  // namespace sphys::test
