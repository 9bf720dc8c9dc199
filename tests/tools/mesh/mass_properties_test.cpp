#include "sphys/tools/mass_properties.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/winding_number.h"
#include "support/mesh_edit.h"

namespace sphys::tools {
namespace {

constexpr double kPi = std::numbers::pi;

double relative_error(double actual, double expected) {
  return std::abs(actual - expected) / std::abs(expected);
}

double relative_error(const Mat3d& actual, const Mat3d& expected) {
  return (actual - expected).norm() / expected.norm();
}

TriangleMesh transformed(TriangleMesh mesh, const Mat3d& rotation, const Vec3d& translation) {
  for (Vec3d& v : mesh.vertices) v = rotation * v + translation;
  return mesh;
}

using test::without_triangles;

MassPropertiesOptions winding_number_options() {
  MassPropertiesOptions options;
  options.force_winding_number = true;
  return options;
}

// A rotation about a skew axis: no axis of the box stays aligned with a mesh axis.
Mat3d skew_rotation() {
  return (Eigen::AngleAxisd(0.9, Vec3d(1.0, -2.0, 0.5).normalized()) *
          Eigen::AngleAxisd(0.4, Vec3d::UnitZ()))
      .toRotationMatrix();
}

TEST(MassProperties, UnitCubeIsExact) {
  // The cube [0, 1]³: I = m/6 about every axis through its centre.
  const TriangleMesh cube =
      transformed(make_box(Vec3d(1.0, 1.0, 1.0)), Mat3d::Identity(), Vec3d(0.5, 0.5, 0.5));
  const MassProperties p = compute_mass_properties(cube);
  const double mass = 1000.0;  // the default density, kg/m³, times 1 m³
  EXPECT_EQ(p.method, MassMethod::Polyhedral);
  EXPECT_LT(relative_error(p.volume, 1.0), 1e-12);
  EXPECT_LT(relative_error(p.mass, mass), 1e-12);
  EXPECT_LT((p.center_of_mass - Vec3d(0.5, 0.5, 0.5)).norm(), 1e-12);
  EXPECT_LT(relative_error(p.inertia, Mat3d::Identity() * mass / 6.0), 1e-9);
  EXPECT_LT((p.principal_moments - Vec3d::Constant(mass / 6.0)).norm(), 1e-9 * mass);
  EXPECT_NEAR(p.principal_axes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, RotatedTranslatedBoxMatchesTheAnalyticTensor) {
  const Vec3d sides(2.0, 3.0, 5.0);
  const Mat3d rotation = skew_rotation();
  const Vec3d translation(10.5, -3.25, 4.0);
  MassPropertiesOptions options;
  options.density = 7.5;
  const MassProperties p =
      compute_mass_properties(transformed(make_box(sides), rotation, translation), options);

  const double volume = sides.prod();
  const double mass = options.density * volume;
  const Vec3d s2 = sides.cwiseProduct(sides);
  // A solid box about its centre: I_x = m (b² + c²) / 12 and so on.
  const Vec3d body_moments = mass / 12.0 * Vec3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
  const Mat3d expected = rotation * body_moments.asDiagonal() * rotation.transpose();

  EXPECT_LT(relative_error(p.volume, volume), 1e-12);
  EXPECT_LT(relative_error(p.mass, mass), 1e-12);
  EXPECT_LT((p.center_of_mass - translation).norm(), 1e-12 * translation.norm());
  EXPECT_LT(relative_error(p.inertia, expected), 1e-9);
  // Ascending: about z (13 m/12), then y (29 m/12), then x (34 m/12).
  const std::array<int, 3> body_axis = {2, 1, 0};
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(relative_error(p.principal_moments[k], body_moments[body_axis[k]]), 1e-9);
    const double alignment = p.principal_axes.col(k).dot(rotation.col(body_axis[k]));
    EXPECT_NEAR(std::abs(alignment), 1.0, 1e-9) << "axis " << k;
  }
  EXPECT_NEAR(p.principal_axes.determinant(), 1.0, 1e-12);
}

TEST(MassProperties, IcosphereConvergesToTheSolidSphere) {
  const double radius = 0.7;
  const double density = 1000.0;
  const double mass = density * 4.0 / 3.0 * kPi * std::pow(radius, 3);
  const double moment = 0.4 * mass * radius * radius;
  // Measured relative errors, s = 2..5: volume 3.4e-2, 8.6e-3, 2.2e-3, 5.4e-4; principal
  // moments 5.6e-2, 1.4e-2, 3.6e-3, 9.0e-4. Each level quarters the error (it is O(h²)).
  double previous_volume_error = 1.0;
  double previous_moment_error = 1.0;
  for (int s = 2; s <= 5; ++s) {
    SCOPED_TRACE(s);
    const MassProperties p = compute_mass_properties(make_icosphere(radius, s));
    EXPECT_EQ(p.method, MassMethod::Polyhedral);
    const double volume_error = relative_error(p.mass, mass);
    double moment_error = 0.0;
    for (int k = 0; k < 3; ++k) {
      moment_error = std::max(moment_error, relative_error(p.principal_moments[k], moment));
    }
    EXPECT_LT(p.center_of_mass.norm(), 1e-12);
    EXPECT_LT(volume_error, previous_volume_error / 3.5);
    EXPECT_LT(moment_error, previous_moment_error / 3.5);
    previous_volume_error = volume_error;
    previous_moment_error = moment_error;
  }
  EXPECT_LT(previous_volume_error, 6e-4);
  EXPECT_LT(previous_moment_error, 1e-3);
}

TEST(MassProperties, TorusConvergesToTheSolidTorus) {
  const double major = 1.0;
  const double minor = 0.4;
  const double mass = 1000.0 * 2.0 * kPi * kPi * major * minor * minor;
  const double axial = mass * (major * major + 0.75 * minor * minor);
  const double perpendicular = mass * (0.5 * major * major + 0.625 * minor * minor);
  // Measured relative errors at 24×12, 48×24, 96×48: volume 5.6e-2, 1.4e-2, 3.6e-3; axial
  // moment 7.1e-2, 1.8e-2, 4.6e-3; perpendicular 7.3e-2, 1.9e-2, 4.7e-3.
  std::array<double, 3> previous = {1.0, 1.0, 1.0};
  for (const int sides : {12, 24, 48}) {
    SCOPED_TRACE(sides);
    const MassProperties p = compute_mass_properties(make_torus(major, minor, 2 * sides, sides));
    const std::array<double, 3> errors = {relative_error(p.mass, mass),
                                          relative_error(p.inertia(1, 1), axial),
                                          std::max(relative_error(p.inertia(0, 0), perpendicular),
                                                   relative_error(p.inertia(2, 2), perpendicular))};
    for (std::size_t k = 0; k < 3; ++k) EXPECT_LT(errors[k], previous[k] / 3.5);
    previous = errors;
    // Symmetric about y: the largest principal moment is the axial one.
    EXPECT_NEAR(p.principal_moments[2], p.inertia(1, 1), 1e-9 * axial);
    EXPECT_LT(p.center_of_mass.norm(), 1e-12);
  }
  EXPECT_LT(previous[0], 4e-3);
  EXPECT_LT(previous[1], 5e-3);
  EXPECT_LT(previous[2], 5e-3);
}

TEST(MassProperties, WindingNumberMethodIsExactForAGridAlignedBox) {
  const MassProperties p =
      compute_mass_properties(make_box(Vec3d(1.0, 1.0, 1.0)), winding_number_options());
  EXPECT_EQ(p.method, MassMethod::WindingNumber);
  EXPECT_LT(relative_error(p.volume, 1.0), 1e-12);
  EXPECT_LT(p.center_of_mass.norm(), 1e-12);
  EXPECT_LT(relative_error(p.inertia, Mat3d::Identity() * p.mass / 6.0), 1e-9);
}

TEST(MassProperties, WindingNumberMethodAgreesWithPolyhedralOnClosedMeshes) {
  // Measured at the default 160 columns: volume within 3.5e-6 (sphere), 8.6e-5 (torus), 7.7e-7
  // (box); inertia within 5.3e-5, 6.7e-5, 6.8e-5: the cells cut by the silhouette. All three are
  // point-symmetric about their bounding-box centre, as is the grid, so the centres of mass agree
  // to rounding.
  const std::vector<TriangleMesh> meshes = {
      make_icosphere(1.0, 4), make_torus(1.0, 0.4, 48, 24),
      transformed(make_box(Vec3d(2.0, 3.0, 5.0)), skew_rotation(), Vec3d(1.0, 2.0, 3.0))};
  for (const TriangleMesh& mesh : meshes) {
    SCOPED_TRACE(mesh.name);
    const MassProperties exact = compute_mass_properties(mesh);
    const MassProperties columns = compute_mass_properties(mesh, winding_number_options());
    EXPECT_EQ(exact.method, MassMethod::Polyhedral);
    EXPECT_EQ(columns.method, MassMethod::WindingNumber);
    EXPECT_LT(relative_error(columns.volume, exact.volume), 2e-4);
    EXPECT_LT(relative_error(columns.inertia, exact.inertia), 2e-4);
    const double size = mesh.bounds().sizes().maxCoeff();
    EXPECT_LT((columns.center_of_mass - exact.center_of_mass).norm(), 1e-12 * size);
  }
}

TEST(MassProperties, WindingNumberMethodIsDeterministic) {
  const TriangleMesh holed = without_triangles(make_icosphere(1.0, 4), {0, 1, 3});
  const MassProperties a = compute_mass_properties(holed);
  const MassProperties b = compute_mass_properties(holed);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.center_of_mass, b.center_of_mass);
  EXPECT_EQ(a.inertia, b.inertia);
}

TEST(MassProperties, PlanarHoleIsClosedExactly) {
  // A unit cube missing any one face: the caps close the hole where the face was, so the column
  // integration is still exact.
  const TriangleMesh cube = make_box(Vec3d(1.0, 1.0, 1.0));
  for (std::size_t face = 0; face < 6; ++face) {
    SCOPED_TRACE(face);
    const MassProperties p =
        compute_mass_properties(without_triangles(cube, {2 * face, 2 * face + 1}));
    EXPECT_EQ(p.method, MassMethod::WindingNumber);
    EXPECT_LT(relative_error(p.volume, 1.0), 1e-12);
    EXPECT_LT(p.center_of_mass.norm(), 1e-12);
    EXPECT_LT(relative_error(p.inertia, Mat3d::Identity() * p.mass / 6.0), 1e-9);
  }
}

TEST(MassProperties, SmallHoleInAnIcosphereBarelyMatters) {
  const double mass = 1000.0 * 4.0 / 3.0 * kPi;
  const double moment = 0.4 * mass;
  const TriangleMesh sphere = make_icosphere(1.0, 4);
  // Three adjacent triangles missing (0 and 1 each share an edge with 3).
  const MassProperties holed = compute_mass_properties(without_triangles(sphere, {0, 1, 3}));
  const MassProperties closed = compute_mass_properties(sphere);
  EXPECT_EQ(holed.method, MassMethod::WindingNumber);
  // Measured: volume 2.2e-3 and moments 3.6e-3 from the analytic sphere (the tessellation's
  // own error), 2.8e-6 and 5.2e-5 from the closed mesh.
  EXPECT_LT(relative_error(holed.mass, mass), 5e-3);
  for (int k = 0; k < 3; ++k) EXPECT_LT(relative_error(holed.principal_moments[k], moment), 5e-3);
  EXPECT_LT(relative_error(holed.volume, closed.volume), 1e-4);
  EXPECT_LT(relative_error(holed.inertia, closed.inertia), 2e-4);
  EXPECT_LT(holed.center_of_mass.norm(), 1e-5);
}

// The fraction of the bounding box with w >= 1/2, by brute force on an n³ lattice.
double lattice_volume(const TriangleMesh& mesh, int n) {
  const Box3d box = mesh.bounds();
  int inside = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const Vec3d fraction = (Vec3d(i, j, k) + Vec3d::Constant(0.5)) / n;
        inside += is_inside(mesh, box.min() + fraction.cwiseProduct(box.sizes())) ? 1 : 0;
      }
    }
  }
  return box.sizes().prod() * inside / (n * n * n);
}

TEST(MassProperties, LargeHoleFollowsTheWindingNumberRegion) {
  // An icosphere without its equatorial band (|y| < 0.3): two cups facing each other. The
  // region w >= 1/2 spans the gap between them; the column method finds it, short by the sliver
  // the level set bulges past the caps sideways, where no column crosses anything (measured:
  // 5.4% below a 20³ lattice estimate, itself good to about 2%).
  const TriangleMesh sphere = make_icosphere(1.0, 2);
  TriangleMesh cups = sphere;
  cups.triangles.clear();
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    const double y = (sphere.corner(t, 0) + sphere.corner(t, 1) + sphere.corner(t, 2)).y() / 3.0;
    if (std::abs(y) >= 0.3) cups.triangles.push_back(sphere.triangles[t]);
  }
  MassPropertiesOptions options;
  options.density = 1.0;
  const double volume = compute_mass_properties(cups, options).volume;
  const double brute_force = lattice_volume(cups, 20);
  EXPECT_GT(volume, 0.9 * brute_force);
  EXPECT_LT(volume, 1.02 * brute_force);
}

// ---- Bad input --------------------------------------------------------------------------------

TriangleMesh named_sphere() {
  TriangleMesh sphere = make_icosphere(1.0, 1);
  sphere.name = "meshes/ball.obj";
  return sphere;
}

TriangleMesh inside_out(TriangleMesh mesh) {
  for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

void expect_error(const TriangleMesh& mesh, const MassPropertiesOptions& options,
                  const std::string& problem) {
  try {
    (void)compute_mass_properties(mesh, options);
    ADD_FAILURE() << "no error for: " << problem;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(mesh.name), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  }
}

TEST(MassProperties, RejectsBadDensity) {
  for (const double density : {-1.0, 0.0, std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity()}) {
    MassPropertiesOptions options;
    options.density = density;
    expect_error(named_sphere(), options, "density must be positive and finite");
  }
}

TEST(MassProperties, RejectsBadColumnCount) {
  MassPropertiesOptions options;
  options.columns = 0;
  expect_error(named_sphere(), options, "columns must be between 1 and");
}

TEST(MassProperties, RejectsInsideOutMeshes) {
  expect_error(inside_out(named_sphere()), {}, "inside out");
  // Open and inside out: the winding number is about -1 inside, so nothing reads as inside.
  const TriangleMesh holed = without_triangles(inside_out(named_sphere()), {0});
  expect_error(holed, {}, "inside out or encloses no volume");
}

TEST(MassProperties, RejectsMeshesThatEncloseNothing) {
  TriangleMesh empty = named_sphere();
  empty.triangles.clear();
  expect_error(empty, {}, "has no triangles");

  // A square made of two triangles back to back: closed, but flat.
  TriangleMesh flat;
  flat.name = "flat.stl";
  flat.vertices = {Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(1, 0, 1)};
  flat.triangles = {{0, 1, 2}, {0, 2, 1}};
  expect_error(flat, {}, "encloses no volume");
  expect_error(flat, winding_number_options(), "encloses no volume");
}

TEST(MassProperties, RejectsBrokenMeshes) {
  TriangleMesh not_finite = named_sphere();
  not_finite.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  expect_error(not_finite, {}, "vertex 3 has a non-finite coordinate");

  TriangleMesh dangling = named_sphere();
  dangling.triangles[5][1] = static_cast<std::uint32_t>(dangling.vertices.size());
  expect_error(dangling, {}, "triangle 5 refers to vertex");
}

}  // namespace
}  // namespace sphys::tools
