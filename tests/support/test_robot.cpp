#include "support/test_robot.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace sphys::test {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

// Ground-truth samples per element, besides the ones on vertices, edges and rims.
constexpr int kRandomSamplesPerElement = 12000;

double to_float(double x) { return static_cast<double>(static_cast<float>(x)); }

Vector3d float_point(double x, double y, double z) {
  return {to_float(x), to_float(y), to_float(z)};
}

// Uniform in [0, 1), the same on every standard library (std::uniform_real_distribution is not).
class UnitRandom {
 public:
  explicit UnitRandom(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
};

// The shortest text that reads back as the same double.
std::string decimal_text(double value) {
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (error != std::errc()) throw std::runtime_error("cannot format a number");
  return {buffer.data(), end};
}

// The shortest text that reads back as the same float (mesh files hold floats).
std::string float_decimal_text(double value) {
  std::array<char, 64> buffer{};
  const auto [end, error] =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), static_cast<float>(value));
  if (error != std::errc()) throw std::runtime_error("cannot format a number");
  return {buffer.data(), end};
}

std::string triple_text(const Vector3d& v) {
  return decimal_text(v.x()) + " " + decimal_text(v.y()) + " " + decimal_text(v.z());
}

// Turns every triangle whose normal points against `outward(centroid)` the other way round.
void orient_outward(RobotMesh& mesh, const std::function<Vector3d(const Vector3d&)>& outward) {
  for (auto& t : mesh.triangles) {
    const Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Vector3d normal = (b - a).cross(c - a);
    if (normal.dot(outward((a + b + c) / 3.0)) < 0.0) std::swap(t[1], t[2]);
  }
}

// The URDF's <origin>: rotation Rz(yaw) Ry(pitch) Rx(roll) (fixed axes X, Y, Z), then the offset.
Eigen::Isometry3d origin_pose(const Vector3d& xyz, const Vector3d& rpy) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()))
                      .toRotationMatrix();
  pose.translation() = xyz;
  return pose;
}

// --- Mesh files ---------------------------------------------------------------------------------

void append_float(std::string& out, double value) {
  const auto f = static_cast<float>(value);
  char bytes[sizeof f];
  std::memcpy(bytes, &f, sizeof f);
  out.append(bytes, sizeof f);
}

Vector3d unit_normal(const RobotMesh& mesh, const std::array<int, 3>& t) {
  const Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
  const Vector3d n = (mesh.vertices[static_cast<std::size_t>(t[1])] - a)
                         .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
  return n.norm() > 0.0 ? Vector3d(n.normalized()) : Vector3d::Zero();
}

std::string binary_stl(const RobotMesh& mesh) {
  std::string out(80, '\0');
  const std::string header = "binary STL written by the sphys robot tests";
  out.replace(0, header.size(), header);
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  char bytes[sizeof count];
  std::memcpy(bytes, &count, sizeof count);  // little-endian, as x86 and STL have it
  out.append(bytes, sizeof count);
  for (const auto& t : mesh.triangles) {
    const Vector3d n = unit_normal(mesh, t);
    for (int k = 0; k < 3; ++k) append_float(out, n[k]);
    for (const int v : t) {
      for (int k = 0; k < 3; ++k) append_float(out, mesh.vertices[static_cast<std::size_t>(v)][k]);
    }
    out.append(2, '\0');
  }
  return out;
}

std::string ascii_stl(const RobotMesh& mesh) {
  std::ostringstream out;
  out << "solid test_robot\n";
  for (const auto& t : mesh.triangles) {
    const Vector3d n = unit_normal(mesh, t);
    out << "  facet normal " << float_decimal_text(n.x()) << ' ' << float_decimal_text(n.y()) << ' '
        << float_decimal_text(n.z()) << "\n    outer loop\n";
    for (const int v : t) {
      const Vector3d& p = mesh.vertices[static_cast<std::size_t>(v)];
      out << "      vertex " << float_decimal_text(p.x()) << ' ' << float_decimal_text(p.y()) << ' '
          << float_decimal_text(p.z()) << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test_robot\n";
  return out.str();
}

std::string obj_text(const RobotMesh& mesh) {
  std::ostringstream out;
  out << "# written by the sphys robot tests\n";
  for (const Vector3d& p : mesh.vertices) {
    out << "v " << float_decimal_text(p.x()) << ' ' << float_decimal_text(p.y()) << ' '
        << float_decimal_text(p.z()) << '\n';
  }
  for (const auto& t : mesh.triangles) {
    out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  return out.str();
}

fs::path mesh_path(const fs::path& dir, const RobotGeometry& g) {
  return g.reference == MeshReference::Package ? dir / kTestRobotPackage / "meshes" / g.file_name
                                               : dir / "robot" / "meshes" / g.file_name;
}

void write_mesh_file(const fs::path& dir, const RobotGeometry& g) {
  const fs::path path = mesh_path(dir, g);
  fs::create_directories(path.parent_path());
  std::string content;
  switch (g.file_type) {
    case MeshFileType::BinaryStl:
      content = binary_stl(g.mesh);
      break;
    case MeshFileType::AsciiStl:
      content = ascii_stl(g.mesh);
      break;
    case MeshFileType::Obj:
      content = obj_text(g.mesh);
      break;
  }
  std::ofstream out(path, std::ios::binary);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  if (!out) throw std::runtime_error("cannot write test mesh " + path.string());
}

// --- URDF ---------------------------------------------------------------------------------------

std::string geometry_xml(const fs::path& dir, const RobotGeometry& g) {
  switch (g.kind) {
    case RobotGeometry::Kind::Box:
      return "<box size=\"" + triple_text(g.size) + "\"/>";
    case RobotGeometry::Kind::Cylinder:
      return "<cylinder radius=\"" + decimal_text(g.radius) + "\" length=\"" +
             decimal_text(g.length) + "\"/>";
    case RobotGeometry::Kind::Sphere:
      return "<sphere radius=\"" + decimal_text(g.radius) + "\"/>";
    case RobotGeometry::Kind::Mesh:
      break;
  }
  std::string uri;
  switch (g.reference) {
    case MeshReference::Relative:
      uri = "meshes/" + g.file_name;
      break;
    case MeshReference::Package:
      uri = std::string("package://") + kTestRobotPackage + "/meshes/" + g.file_name;
      break;
    case MeshReference::FileUri:
      uri = "file://" + fs::absolute(mesh_path(dir, g)).string();
      break;
  }
  std::string xml = "<mesh filename=\"" + uri + "\"";
  if (g.scale) xml += " scale=\"" + triple_text(*g.scale) + "\"";
  return xml + "/>";
}

std::string element_xml(const fs::path& dir, const char* tag, const RobotGeometry& g) {
  return std::string("    <") + tag + ">\n      <origin xyz=\"" + triple_text(g.xyz) + "\" rpy=\"" +
         triple_text(g.rpy) + "\"/>\n      <geometry>\n        " + geometry_xml(dir, g) +
         "\n      </geometry>\n    </" + tag + ">\n";
}

// --- Ground truth -------------------------------------------------------------------------------

void add_segment(std::vector<Vector3d>& samples, const Vector3d& a, const Vector3d& b, int steps) {
  for (int i = 1; i < steps; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(steps);
    samples.push_back((1.0 - t) * a + t * b);
  }
}

// Mesh samples in the link's frame: vertices, edges, centroids, area-weighted random points.
void sample_mesh(const RobotGeometry& g, const Eigen::Isometry3d& pose, UnitRandom& random,
                 LinkTruth& truth) {
  const Vector3d scale = g.scale.value_or(Vector3d::Ones());
  std::vector<Vector3d> v;
  v.reserve(g.mesh.vertices.size());
  for (const Vector3d& p : g.mesh.vertices) v.push_back(pose * scale.cwiseProduct(p));
  std::vector<double> cumulative;
  double area = 0.0;
  for (const auto& t : g.mesh.triangles) {
    const Vector3d& a = v[static_cast<std::size_t>(t[0])];
    const Vector3d& b = v[static_cast<std::size_t>(t[1])];
    const Vector3d& c = v[static_cast<std::size_t>(t[2])];
    truth.samples.push_back((a + b + c) / 3.0);
    add_segment(truth.samples, a, b, 8);
    add_segment(truth.samples, b, c, 8);
    add_segment(truth.samples, c, a, 8);
    area += 0.5 * (b - a).cross(c - a).norm();
    cumulative.push_back(area);
  }
  for (const Vector3d& p : v) {
    truth.samples.push_back(p);
    truth.bounds.extend(p);
  }
  for (int i = 0; i < kRandomSamplesPerElement && area > 0.0; ++i) {
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), random() * area);
    const auto& t = g.mesh.triangles[static_cast<std::size_t>(std::min<std::ptrdiff_t>(
        it - cumulative.begin(), static_cast<std::ptrdiff_t>(cumulative.size()) - 1))];
    const double s = std::sqrt(random());
    const double r = random();
    truth.samples.push_back((1.0 - s) * v[static_cast<std::size_t>(t[0])] +
                            s * (1.0 - r) * v[static_cast<std::size_t>(t[1])] +
                            s * r * v[static_cast<std::size_t>(t[2])]);
  }
}

// A box from its faces: corners, edges, a grid and random points on each face.
std::vector<Vector3d> box_samples(const Vector3d& size, UnitRandom& random) {
  const Vector3d h = size / 2.0;
  std::vector<Vector3d> samples;
  std::vector<Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                         (i & 4) ? h.z() : -h.z());
  }
  samples = corners;
  for (int i = 0; i < 8; ++i) {
    for (const int bit : {1, 2, 4}) {
      if ((i & bit) == 0) add_segment(samples, corners[i], corners[i | bit], 32);
    }
  }
  const double total = 2.0 * (size.x() * size.y() + size.y() * size.z() + size.z() * size.x());
  for (int axis = 0; axis < 3; ++axis) {
    const int b = (axis + 1) % 3;
    const int c = (axis + 2) % 3;
    const double face = size[b] * size[c];
    const int random_points =
        static_cast<int>(kRandomSamplesPerElement * face / std::max(total, 1e-300));
    for (const double side : {-1.0, 1.0}) {
      Vector3d p = Vector3d::Zero();
      p[axis] = side * h[axis];
      for (int i = 0; i <= 10; ++i) {
        for (int j = 0; j <= 10; ++j) {
          p[b] = -h[b] + size[b] * i / 10.0;
          p[c] = -h[c] + size[c] * j / 10.0;
          samples.push_back(p);
        }
      }
      for (int i = 0; i < random_points / 2; ++i) {
        p[b] = -h[b] + size[b] * random();
        p[c] = -h[c] + size[c] * random();
        samples.push_back(p);
      }
    }
  }
  return samples;
}

// A cylinder along z from its equation: both rims, side lines, random side and cap points.
std::vector<Vector3d> cylinder_samples(double radius, double length, UnitRandom& random) {
  std::vector<Vector3d> samples;
  const double h = length / 2.0;
  const double tau = 2.0 * std::numbers::pi;
  constexpr int kRim = 2048;
  for (int i = 0; i < kRim; ++i) {
    const double a = tau * i / kRim;
    for (const double z : {-h, h})
      samples.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    if (i % 4 == 0) {
      for (int j = 1; j < 16; ++j) {
        samples.emplace_back(radius * std::cos(a), radius * std::sin(a), -h + length * j / 16.0);
      }
    }
  }
  const double side = tau * radius * length;
  const double caps = tau * radius * radius;
  const int side_points = static_cast<int>(kRandomSamplesPerElement * side / (side + caps));
  for (int i = 0; i < side_points; ++i) {
    const double a = tau * random();
    samples.emplace_back(radius * std::cos(a), radius * std::sin(a), -h + length * random());
  }
  for (const double z : {-h, h}) {
    samples.emplace_back(0.0, 0.0, z);
    for (int i = 0; i < (kRandomSamplesPerElement - side_points) / 2; ++i) {
      const double a = tau * random();
      const double r = radius * std::sqrt(random());
      samples.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  return samples;
}

// A sphere from its equation: a Fibonacci lattice, the poles and random points.
std::vector<Vector3d> sphere_samples(double radius, UnitRandom& random) {
  std::vector<Vector3d> samples;
  constexpr int kLattice = 4000;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kLattice; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kLattice;
    const double r = std::sqrt(1.0 - z * z);
    samples.push_back(radius * Vector3d(r * std::cos(golden * i), r * std::sin(golden * i), z));
  }
  for (int k = 0; k < 3; ++k) {
    samples.push_back(radius * Vector3d::Unit(k));
    samples.push_back(-radius * Vector3d::Unit(k));
  }
  for (int i = 0; i < kRandomSamplesPerElement - kLattice; ++i) {
    const double z = 1.0 - 2.0 * random();
    const double a = 2.0 * std::numbers::pi * random();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    samples.push_back(radius * Vector3d(r * std::cos(a), r * std::sin(a), z));
  }
  return samples;
}

void sample_element(const RobotGeometry& g, UnitRandom& random, LinkTruth& truth) {
  const Eigen::Isometry3d pose = origin_pose(g.xyz, g.rpy);
  std::vector<Vector3d> local;
  switch (g.kind) {
    case RobotGeometry::Kind::Mesh:
      sample_mesh(g, pose, random, truth);
      truth.sources.push_back(g.file_name);
      return;
    case RobotGeometry::Kind::Box: {
      local = box_samples(g.size, random);
      const Vector3d h = g.size / 2.0;
      for (int i = 0; i < 8; ++i) {
        truth.bounds.extend(pose * Vector3d((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                            (i & 4) ? h.z() : -h.z()));
      }
      truth.sources.emplace_back("box");
      break;
    }
    case RobotGeometry::Kind::Cylinder: {
      local = cylinder_samples(g.radius, g.length, random);
      // Along each axis k the cylinder reaches h |a_k| + r sqrt(1 - a_k²) from its centre.
      const Vector3d axis = pose.linear() * Vector3d::UnitZ();
      Vector3d reach;
      for (int k = 0; k < 3; ++k) {
        reach[k] = g.length / 2.0 * std::abs(axis[k]) +
                   g.radius * std::sqrt(std::max(0.0, 1.0 - axis[k] * axis[k]));
      }
      truth.bounds.extend(pose.translation() - reach);
      truth.bounds.extend(pose.translation() + reach);
      truth.curved_primitive = true;
      truth.sources.emplace_back("cylinder");
      break;
    }
    case RobotGeometry::Kind::Sphere:
      local = sphere_samples(g.radius, random);
      truth.bounds.extend(pose.translation() - Vector3d::Constant(g.radius));
      truth.bounds.extend(pose.translation() + Vector3d::Constant(g.radius));
      truth.curved_primitive = true;
      truth.sources.emplace_back("sphere");
      break;
  }
  for (const Vector3d& p : local) truth.samples.push_back(pose * p);
}

}  // namespace

RobotMesh box_mesh(const Vector3d& size) {
  RobotMesh mesh;
  const Vector3d h = size / 2.0;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.push_back(
        float_point((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
  }
  // Each face: its four corners in order around it, as two triangles.
  for (int axis = 0; axis < 3; ++axis) {
    const int b = 1 << ((axis + 1) % 3);
    const int c = 1 << ((axis + 2) % 3);
    for (const int side : {0, 1 << axis}) {
      const std::array<int, 4> q = {side, side | b, side | b | c, side | c};
      mesh.triangles.push_back({q[0], q[1], q[2]});
      mesh.triangles.push_back({q[0], q[2], q[3]});
    }
  }
  orient_outward(mesh, [](const Vector3d& p) { return p; });
  return mesh;
}

RobotMesh torus_mesh(double ring_radius, double tube_radius, int ring_segments, int tube_segments) {
  RobotMesh mesh;
  const double tau = 2.0 * std::numbers::pi;
  for (int i = 0; i < ring_segments; ++i) {
    const double u = tau * i / ring_segments;
    for (int j = 0; j < tube_segments; ++j) {
      const double v = tau * j / tube_segments;
      const double r = ring_radius + tube_radius * std::cos(v);
      mesh.vertices.push_back(
          float_point(r * std::cos(u), r * std::sin(u), tube_radius * std::sin(v)));
    }
  }
  const auto index = [&](int i, int j) {
    return (i % ring_segments) * tube_segments + (j % tube_segments);
  };
  for (int i = 0; i < ring_segments; ++i) {
    for (int j = 0; j < tube_segments; ++j) {
      mesh.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  orient_outward(mesh, [ring_radius](const Vector3d& p) {
    const double u = std::atan2(p.y(), p.x());
    return Vector3d(p - ring_radius * Vector3d(std::cos(u), std::sin(u), 0.0));
  });
  return mesh;
}

RobotMesh capsule_mesh(double radius, double half_length, int segments, int rings_per_cap) {
  RobotMesh mesh;
  const double tau = 2.0 * std::numbers::pi;
  // Rings from bottom to top: the lower cap's (ending at its equator), the upper cap's.
  std::vector<std::pair<double, double>> rings;  // height, radius
  for (int k = 1; k <= rings_per_cap; ++k) {
    const double latitude = -std::numbers::pi / 2.0 + std::numbers::pi / 2.0 * k / rings_per_cap;
    rings.emplace_back(-half_length + radius * std::sin(latitude), radius * std::cos(latitude));
  }
  for (int k = 0; k < rings_per_cap; ++k) {
    const double latitude = std::numbers::pi / 2.0 * k / rings_per_cap;
    rings.emplace_back(half_length + radius * std::sin(latitude), radius * std::cos(latitude));
  }
  const int bottom = 0;
  mesh.vertices.push_back(float_point(0.0, 0.0, -half_length - radius));
  for (const auto& [z, r] : rings) {
    for (int i = 0; i < segments; ++i) {
      const double a = tau * i / segments;
      mesh.vertices.push_back(float_point(r * std::cos(a), r * std::sin(a), z));
    }
  }
  const int top = static_cast<int>(mesh.vertices.size());
  mesh.vertices.push_back(float_point(0.0, 0.0, half_length + radius));
  const auto index = [segments](int ring, int i) { return 1 + ring * segments + i % segments; };
  const int ring_count = static_cast<int>(rings.size());
  for (int i = 0; i < segments; ++i) {
    mesh.triangles.push_back({bottom, index(0, i + 1), index(0, i)});
    for (int k = 0; k + 1 < ring_count; ++k) {
      mesh.triangles.push_back({index(k, i), index(k, i + 1), index(k + 1, i + 1)});
      mesh.triangles.push_back({index(k, i), index(k + 1, i + 1), index(k + 1, i)});
    }
    mesh.triangles.push_back({top, index(ring_count - 1, i), index(ring_count - 1, i + 1)});
  }
  orient_outward(mesh, [half_length](const Vector3d& p) {
    return Vector3d(p - Vector3d(0.0, 0.0, std::clamp(p.z(), -half_length, half_length)));
  });
  return mesh;
}

RobotMesh scaled_mesh(const RobotMesh& mesh, double factor) {
  RobotMesh out = mesh;
  for (Vector3d& p : out.vertices) p = float_point(p.x() * factor, p.y() * factor, p.z() * factor);
  return out;
}

RobotGeometry box_geometry(const Vector3d& size, const Vector3d& xyz, const Vector3d& rpy) {
  RobotGeometry g;
  g.kind = RobotGeometry::Kind::Box;
  g.size = size;
  g.xyz = xyz;
  g.rpy = rpy;
  return g;
}

RobotGeometry cylinder_geometry(double radius, double length, const Vector3d& xyz,
                                const Vector3d& rpy) {
  RobotGeometry g;
  g.kind = RobotGeometry::Kind::Cylinder;
  g.radius = radius;
  g.length = length;
  g.xyz = xyz;
  g.rpy = rpy;
  return g;
}

RobotGeometry sphere_geometry(double radius, const Vector3d& xyz) {
  RobotGeometry g;
  g.kind = RobotGeometry::Kind::Sphere;
  g.radius = radius;
  g.xyz = xyz;
  return g;
}

RobotGeometry mesh_geometry(RobotMesh mesh, std::string file_name, MeshFileType type,
                            MeshReference reference, const Vector3d& xyz, const Vector3d& rpy,
                            std::optional<Vector3d> scale) {
  RobotGeometry g;
  g.kind = RobotGeometry::Kind::Mesh;
  g.mesh = std::move(mesh);
  g.file_name = std::move(file_name);
  g.file_type = type;
  g.reference = reference;
  g.xyz = xyz;
  g.rpy = rpy;
  g.scale = scale;
  return g;
}

RobotSpec standard_test_robot() {
  constexpr double kQuarter = std::numbers::pi / 2.0;
  RobotSpec robot;
  robot.name = "test_robot";
  robot.links = {
      {"base_link",
       {box_geometry({0.30, 0.30, 0.10}, {0.0, 0.0, 0.05})},
       {cylinder_geometry(0.2, 0.1, {0.0, 0.0, 0.05})}},
      {"shoulder_link",
       {cylinder_geometry(0.06, 0.12, {0.0, 0.01, 0.06}, {0.0, 0.0, 0.3}),
        box_geometry({0.05, 0.14, 0.05}, {0.0, 0.0, 0.12}, {0.0, 0.0, 0.4})},
       {}},
      {"upper_arm_link",
       {mesh_geometry(torus_mesh(0.08, 0.03, 40, 16), "upper_arm.stl", MeshFileType::BinaryStl,
                      MeshReference::Relative, {0.02, -0.01, 0.15}, {kQuarter, 0.2, 0.3},
                      Vector3d(1.2, 1.0, 0.8))},
       {mesh_geometry(torus_mesh(0.08, 0.03, 40, 16), "upper_arm.stl", MeshFileType::BinaryStl,
                      MeshReference::Relative, {0.02, -0.01, 0.15}, {kQuarter, 0.2, 0.3},
                      Vector3d(1.2, 1.0, 0.8))}},
      {"forearm_link",
       {mesh_geometry(capsule_mesh(0.035, 0.09, 24, 6), "forearm.obj", MeshFileType::Obj,
                      MeshReference::Package, {0.0, 0.0, 0.125}, {0.0, 0.1, 0.0})},
       {}},
      {"hand_link",
       {},
       {mesh_geometry(box_mesh({0.08, 0.10, 0.04}), "hand_palm.stl", MeshFileType::AsciiStl,
                      MeshReference::FileUri, {0.0, 0.0, 0.02}, {0.0, 0.0, 0.25},
                      Vector3d(1.0, 1.0, 1.0)),
        sphere_geometry(0.03, {0.0, 0.0, 0.05})}},
      {"finger_left_link",
       {mesh_geometry(box_mesh({0.002, 0.020, 0.050}), "finger.stl", MeshFileType::BinaryStl,
                      MeshReference::Relative, {0.0, 0.0, 0.025})},
       {}},
      {"finger_right_link",
       {mesh_geometry(box_mesh({2.0, 20.0, 50.0}), "finger_mm.obj", MeshFileType::Obj,
                      MeshReference::Relative, {0.0, 0.0, 0.025}, {0.0, 0.0, std::numbers::pi},
                      Vector3d(0.001, 0.001, 0.001))},
       {}},
      {"tool0", {}, {}},
  };
  robot.joints = {
      {"shoulder_pan",
       "revolute",
       "base_link",
       "shoulder_link",
       {0.0, 0.0, 0.10},
       {0.0, 0.0, 0.0},
       {0.0, 0.0, 1.0},
       -3.1,
       3.1},
      {"shoulder_lift",
       "revolute",
       "shoulder_link",
       "upper_arm_link",
       {0.0, 0.0, 0.14},
       {0.0, 0.0, 0.0},
       {0.0, 1.0, 0.0},
       -2.0,
       2.0},
      {"elbow",
       "revolute",
       "upper_arm_link",
       "forearm_link",
       {0.0, 0.0, 0.30},
       {0.0, 0.2, 0.0},
       {0.0, 1.0, 0.0},
       -2.5,
       2.5},
      {"wrist",
       "fixed",
       "forearm_link",
       "hand_link",
       {0.0, 0.0, 0.25},
       {0.0, 0.0, kQuarter},
       {0.0, 0.0, 1.0},
       0.0,
       0.0},
      {"finger_left_joint",
       "prismatic",
       "hand_link",
       "finger_left_link",
       {0.0, 0.02, 0.09},
       {0.0, 0.0, 0.0},
       {0.0, 1.0, 0.0},
       0.0,
       0.03},
      {"finger_right_joint",
       "prismatic",
       "hand_link",
       "finger_right_link",
       {0.0, -0.02, 0.09},
       {0.0, 0.0, 0.0},
       {0.0, -1.0, 0.0},
       0.0,
       0.03},
      {"tool0_joint",
       "fixed",
       "hand_link",
       "tool0",
       {0.0, 0.0, 0.12},
       {0.0, 0.0, 0.0},
       {0.0, 0.0, 1.0},
       0.0,
       0.0},
  };
  return robot;
}

std::string test_robot_urdf(const fs::path& dir, const RobotSpec& spec) {
  std::string xml = "<?xml version=\"1.0\"?>\n<robot name=\"" + spec.name + "\">\n";
  for (const RobotLinkSpec& link : spec.links) {
    if (link.collisions.empty() && link.visuals.empty()) {
      xml += "  <link name=\"" + link.name + "\"/>\n";
      continue;
    }
    xml += "  <link name=\"" + link.name + "\">\n";
    for (const RobotGeometry& g : link.visuals) xml += element_xml(dir, "visual", g);
    for (const RobotGeometry& g : link.collisions) xml += element_xml(dir, "collision", g);
    xml += "  </link>\n";
  }
  for (const RobotJointSpec& joint : spec.joints) {
    xml += "  <joint name=\"" + joint.name + "\" type=\"" + joint.type + "\">\n";
    xml += "    <parent link=\"" + joint.parent + "\"/>\n";
    xml += "    <child link=\"" + joint.child + "\"/>\n";
    xml += "    <origin xyz=\"" + triple_text(joint.xyz) + "\" rpy=\"" + triple_text(joint.rpy) +
           "\"/>\n";
    if (joint.type != "fixed") {
      xml += "    <axis xyz=\"" + triple_text(joint.axis) + "\"/>\n";
      xml += "    <limit lower=\"" + decimal_text(joint.lower) + "\" upper=\"" +
             decimal_text(joint.upper) + "\" effort=\"10\" velocity=\"1\"/>\n";
    }
    xml += "  </joint>\n";
  }
  return xml + "</robot>\n";
}

TestRobot write_test_robot(const fs::path& dir, const RobotSpec& spec) {
  TestRobot robot;
  robot.name = spec.name;
  robot.urdf = dir / "robot" / (spec.name + ".urdf");
  robot.package_dir = dir / kTestRobotPackage;
  robot.package_option = std::string(kTestRobotPackage) + "=" + robot.package_dir.string();
  fs::create_directories(dir / "robot" / "meshes");
  fs::create_directories(robot.package_dir / "meshes");
  std::uint64_t seed = 20240611;
  for (const RobotLinkSpec& link : spec.links) {
    robot.links.push_back(link.name);
    for (const auto* elements : {&link.collisions, &link.visuals}) {
      for (const RobotGeometry& g : *elements) {
        if (g.kind == RobotGeometry::Kind::Mesh) write_mesh_file(dir, g);
      }
    }
    const bool from_visual = link.collisions.empty();
    const std::vector<RobotGeometry>& counted = from_visual ? link.visuals : link.collisions;
    if (counted.empty()) continue;
    robot.links_with_geometry.push_back(link.name);
    LinkTruth& truth = robot.truth[link.name];
    truth.from_visual = from_visual;
    UnitRandom random(seed++);
    for (const RobotGeometry& g : counted) sample_element(g, random, truth);
  }
  const std::string xml = test_robot_urdf(dir, spec);
  std::ofstream out(robot.urdf, std::ios::binary);
  out << xml;
  if (!out) throw std::runtime_error("cannot write " + robot.urdf.string());
  return robot;
}

}  // namespace sphys::test
