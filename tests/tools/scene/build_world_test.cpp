#include "sphys/tools/build_world.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/scenarios.h"
#include "sphys/tools/sph_file.h"
#include "support/obj_text.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;

// A body whose tree is a quick octree: the tests that use it do not depend on the method.
BodySpec octree_body(const std::string& mesh, int depth = 2) {
  BodySpec body;
  body.mesh = mesh;
  body.tree.method = BuildMethod::Octree;
  body.tree.depth = depth;
  return body;
}

Scene scene_without_ground(std::vector<BodySpec> bodies) {
  Scene scene;
  scene.name = "test scene";
  scene.ground.kind = GroundSpec::Kind::kNone;
  scene.bodies = std::move(bodies);
  return scene;
}

using test::obj_text;

BuildWorldOptions with_tree_depth(int depth) {
  BuildWorldOptions options;
  options.tree_depth = depth;
  return options;
}

// Relative comparison of two inertia tensors, entry by entry against the largest entry.
void expect_inertia_near(const Mat3& actual, const Mat3d& expected, double relative) {
  const double scale = expected.cwiseAbs().maxCoeff();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(actual(r, c), expected(r, c), relative * scale)
          << "inertia(" << r << ", " << c << ")";
    }
  }
}

TEST(BuildWorld, BodiesOfOneStackShareOneShape) {
  Scene scene = bunny_stacks_scene(1, 3, 2);
  scene.ground.kind = GroundSpec::Kind::kNone;
  for (BodySpec& body : scene.bodies) body.tree.method = BuildMethod::Octree;
  const SimulationSetup setup = build_world(scene);
  ASSERT_EQ(setup.bodies.size(), 3u);
  ASSERT_EQ(setup.shapes.size(), 1u);
  EXPECT_THAT(setup.body_shape, ElementsAre(0u, 0u, 0u));
  EXPECT_EQ(setup.shapes[0].mesh, "bunny");
  EXPECT_EQ(setup.shapes[0].tree->depth(), 2);
  EXPECT_THAT(setup.shapes[0].tree_source, HasSubstr("octree, branching 8, depth 2"));
  EXPECT_FALSE(setup.ground.has_value());
  EXPECT_EQ(setup.world->body_slots(), 3u);
  // The bodies are where the scene puts them.
  for (std::size_t i = 0; i < 3; ++i) {
    const RigidBody& body = setup.world->body(setup.bodies[i]);
    EXPECT_EQ(body.pose.translation, scene.bodies[i].position);
    EXPECT_TRUE(body.pose.rotation.isApprox(scene.bodies[i].orientation));
    EXPECT_FALSE(body.is_static);
  }
}

TEST(BuildWorld, ADifferentSizeOrTreeMakesANewShape) {
  BodySpec small = octree_body("bunny", 1);
  small.size = 0.5;
  BodySpec deeper = octree_body("bunny", 2);
  const Scene scene = scene_without_ground(
      {octree_body("bunny", 1), small, octree_body("bunny", 1), deeper, small});
  const SimulationSetup setup = build_world(scene);
  ASSERT_EQ(setup.shapes.size(), 3u);
  EXPECT_THAT(setup.body_shape, ElementsAre(0u, 1u, 0u, 2u, 1u));
  EXPECT_EQ(setup.shapes[2].tree->depth(), 2);
  // Same mesh file, so the sizes tell the shapes apart.
  EXPECT_NEAR(setup.shapes[1].max_vertex_distance * 2.0, setup.shapes[0].max_vertex_distance, 1e-9);
}

TEST(BuildWorld, MassIsDensityTimesTheMeshVolume) {
  BodySpec light = octree_body("bunny", 1);
  light.density = 800.0;
  BodySpec heavy = light;
  heavy.mass = 12.5;
  const SimulationSetup setup = build_world(scene_without_ground({light, heavy}));
  ASSERT_EQ(setup.shapes.size(), 1u);
  const BodyShape& shape = setup.shapes[0];
  const MassProperties expected = compute_mass_properties(*shape.body_mesh, {.density = 800.0});
  EXPECT_NEAR(shape.volume, expected.volume, 1e-12);
  // The unit-size bunny encloses a fraction of its 1 m bounding box; a sanity bound on the
  // figure everything else scales from.
  EXPECT_GT(expected.volume, 0.1);
  EXPECT_LT(expected.volume, 0.5);

  const RigidBody& by_density = setup.world->body(setup.bodies[0]);
  EXPECT_NEAR(by_density.mass(), expected.mass, 1e-5 * expected.mass);
  expect_inertia_near(by_density.inertia_body, expected.inertia, 1e-5);

  // A given mass replaces density times volume; the inertia scales with it.
  const RigidBody& by_mass = setup.world->body(setup.bodies[1]);
  EXPECT_NEAR(by_mass.mass(), 12.5, 1e-5);
  expect_inertia_near(by_mass.inertia_body, expected.inertia * (12.5 / expected.mass), 1e-5);
}

TEST(BuildWorld, BoxMassPropertiesMatchTheClosedForm) {
  const test::TempDir dir;
  // A 2 x 1 x 0.5 box scaled to size 1 becomes 1 x 0.5 x 0.25: volume 0.125 m³.
  const auto box = dir.write("box.obj", obj_text(make_box({2.0, 1.0, 0.5})));
  BodySpec body = octree_body(box.string(), 1);
  body.size = 1.0;
  body.density = 1000.0;
  const SimulationSetup setup = build_world(scene_without_ground({body}));
  const RigidBody& built = setup.world->body(setup.bodies[0]);
  const double mass = 125.0;
  EXPECT_NEAR(setup.shapes[0].volume, 0.125, 1e-12);
  EXPECT_NEAR(built.mass(), mass, 1e-4);
  // A box of sides a, b, c: I_xx = m (b² + c²) / 12 and so on, no products of inertia.
  Mat3d expected = Mat3d::Zero();
  expected(0, 0) = mass * (0.5 * 0.5 + 0.25 * 0.25) / 12.0;
  expected(1, 1) = mass * (1.0 + 0.25 * 0.25) / 12.0;
  expected(2, 2) = mass * (1.0 + 0.5 * 0.5) / 12.0;
  expect_inertia_near(built.inertia_body, expected, 1e-5);
}

TEST(BuildWorld, BodyMeshIsCentredOnItsCentreOfMassAndScaledToItsSize) {
  BodySpec bunny = octree_body("bunny", 1);
  bunny.size = 0.5;
  const SimulationSetup setup = build_world(scene_without_ground({bunny}));
  const TriangleMesh& mesh = *setup.shapes[0].body_mesh;
  EXPECT_NEAR(mesh.bounds().sizes().maxCoeff(), 0.5, 1e-9);
  EXPECT_LT(compute_mass_properties(mesh).center_of_mass.norm(), 1e-9);
  double farthest = 0.0;
  for (const Vec3d& v : mesh.vertices) farthest = std::max(farthest, v.norm());
  EXPECT_DOUBLE_EQ(setup.shapes[0].max_vertex_distance, farthest);
  // Every vertex lies inside the root sphere of the body's tree: tree and mesh share the frame.
  const Sphere& root = setup.shapes[0].tree->sphere(0);
  for (const Vec3d& v : mesh.vertices) {
    EXPECT_LE((v.cast<float>() - root.center).norm(), root.radius * 1.0001f);
  }
}

TEST(BuildWorld, MeshKeepsItsSizeWhenNoneIsGivenButIsStillCentred) {
  const test::TempDir dir;
  const auto box =
      dir.write("far_box.obj", obj_text(make_box({2.0, 1.0, 0.5}), Vec3d(5.0, -3.0, 2.0)));
  BodySpec body = octree_body(box.string(), 1);
  body.size.reset();
  const SimulationSetup setup = build_world(scene_without_ground({body}));
  const TriangleMesh& mesh = *setup.shapes[0].body_mesh;
  EXPECT_TRUE(mesh.bounds().sizes().isApprox(Vec3d(2.0, 1.0, 0.5), 1e-9));
  EXPECT_LT(mesh.bounds().center().norm(), 1e-6);
  EXPECT_NEAR(setup.shapes[0].volume, 1.0, 1e-9);
}

TEST(BuildWorld, TreeDepthOptionOverridesTheScene) {
  const Scene scene = scene_without_ground({octree_body("bunny", 1)});
  EXPECT_EQ(build_world(scene).shapes[0].tree->depth(), 1);
  const SimulationSetup setup = build_world(scene, with_tree_depth(2));
  EXPECT_EQ(setup.shapes[0].tree->depth(), 2);
  EXPECT_THAT(setup.shapes[0].tree_source, HasSubstr("depth 2"));

  for (int bad : {0, 7}) {
    try {
      (void)build_world(scene, with_tree_depth(bad));
      ADD_FAILURE() << "tree depth " << bad << " accepted";
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr("depth must be 1 to 6, got " + std::to_string(bad)));
    }
  }
}

TEST(BuildWorld, TreeDepthOptionCutsTreesReadFromFiles) {
  const test::TempDir dir;
  BuildOptions octree;
  octree.method = BuildMethod::Octree;
  octree.depth = 3;
  const auto sph = dir.path() / "box.sph";
  write_sph(sph, build_sphere_tree(make_box({1.0, 0.5, 0.5}), octree));
  const auto box = dir.write("box.obj", obj_text(make_box({1.0, 0.5, 0.5})));
  BodySpec body = octree_body(box.string());
  body.tree.sph_file = sph;

  const Scene scene = scene_without_ground({body});
  EXPECT_EQ(build_world(scene).shapes[0].tree->depth(), 3);
  const SimulationSetup cut = build_world(scene, with_tree_depth(2));
  EXPECT_EQ(cut.shapes[0].tree->depth(), 2);
  EXPECT_THAT(cut.shapes[0].tree_source, HasSubstr("cut to depth 2"));
  // A deeper request cannot deepen a file's tree.
  EXPECT_EQ(build_world(scene, with_tree_depth(5)).shapes[0].tree->depth(), 3);
}

TEST(BuildWorld, OctreeBoxGroundIsAStaticBody) {
  Scene scene = scene_without_ground({octree_body("bunny", 1)});
  scene.ground.kind = GroundSpec::Kind::kOctreeBox;
  scene.ground.height = 0.25;
  scene.ground.depth = 2;
  const SimulationSetup setup = build_world(scene);
  ASSERT_TRUE(setup.ground.has_value());
  EXPECT_EQ(setup.world->body_slots(), 2u);
  EXPECT_EQ(setup.bodies.size(), 1u);
  EXPECT_NE(setup.bodies[0], *setup.ground);
  const RigidBody& ground = setup.world->body(*setup.ground);
  EXPECT_TRUE(ground.is_static);
  EXPECT_EQ(ground.pose.translation, Vec3(0.0f, 0.25f, 0.0f));
  EXPECT_FALSE(setup.world->settings().collision.ground_plane_height.has_value());
}

TEST(BuildWorld, PlaneGroundIsTheDetectorsGroundPlane) {
  Scene scene = scene_without_ground({octree_body("bunny", 1)});
  scene.ground.kind = GroundSpec::Kind::kPlane;
  scene.ground.height = -0.5;
  scene.ground.restitution = 0.7f;
  scene.ground.friction = 0.2f;
  const SimulationSetup setup = build_world(scene);
  EXPECT_FALSE(setup.ground.has_value());
  EXPECT_EQ(setup.world->body_slots(), 1u);
  const WorldSettings& settings = setup.world->settings();
  ASSERT_TRUE(settings.collision.ground_plane_height.has_value());
  EXPECT_EQ(*settings.collision.ground_plane_height, -0.5f);
  EXPECT_EQ(settings.ground_restitution, 0.7f);
  EXPECT_EQ(settings.ground_friction, 0.2f);

  scene.ground.kind = GroundSpec::Kind::kNone;
  const SimulationSetup none = build_world(scene);
  EXPECT_FALSE(none.ground.has_value());
  EXPECT_FALSE(none.world->settings().collision.ground_plane_height.has_value());
}

// The message of the Error that building `scene` throws.
std::string build_error(const Scene& scene) {
  try {
    (void)build_world(scene);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for " << scene.name;
  return "";
}

TEST(BuildWorld, SceneSettingsReachTheWorld) {
  Scene scene = scene_without_ground({});
  scene.gravity = Vec3(0.0f, -1.62f, 0.5f);
  scene.response = ResponseMode::kPaper;
  scene.paper_passes = 4;
  scene.collision_passes = 3;
  scene.max_collision_passes = 5;
  scene.collision_pass_travel = 0.3f;
  scene.solver.soft_substeps = 7;
  scene.solver.contact_hertz = 20.0f;
  scene.solver.contact_damping_ratio = 2.0f;
  scene.solver.warm_starting = false;
  scene.solver.restitution_threshold = 0.25f;
  scene.solver.linear_slop = 0.01f;
  scene.solver.max_correction_speed = 1.5f;
  scene.solver.contacts = ContactSet::kAll;
  scene.solver.manifold_points = 7;
  scene.solver.contact_margin = 0.04f;
  scene.solver.speculative_contacts = false;
  scene.sleep = {.enabled = false, .speed = 0.2f, .time = 1.25f};
  const SimulationSetup setup = build_world(scene);
  const WorldSettings& settings = setup.world->settings();
  EXPECT_EQ(settings.gravity, Vec3(0.0f, -1.62f, 0.5f));
  EXPECT_EQ(settings.response, ResponseMode::kPaper);
  EXPECT_EQ(settings.paper_passes, 4u);
  EXPECT_EQ(settings.collision_passes, 3u);
  EXPECT_EQ(settings.max_collision_passes, 5u);
  EXPECT_EQ(settings.collision_pass_travel, 0.3f);
  const SolverSettings& solver = settings.solver;
  EXPECT_EQ(solver.soft_substeps, 7u);
  EXPECT_EQ(solver.contact_hertz, 20.0f);
  EXPECT_EQ(solver.contact_damping_ratio, 2.0f);
  EXPECT_FALSE(solver.warm_starting);
  EXPECT_EQ(solver.restitution_threshold, 0.25f);
  EXPECT_EQ(solver.linear_slop, 0.01f);
  EXPECT_EQ(solver.max_correction_speed, 1.5f);
  EXPECT_EQ(solver.contacts, ContactSet::kAll);
  EXPECT_EQ(solver.manifold_points, 7u);
  EXPECT_EQ(solver.contact_margin, 0.04f);
  EXPECT_FALSE(solver.speculative_contacts);
  EXPECT_FALSE(settings.sleep.enabled);
  EXPECT_EQ(settings.sleep.speed, 0.2f);
  EXPECT_EQ(settings.sleep.time, 1.25f);
  EXPECT_TRUE(setup.bodies.empty());
  EXPECT_TRUE(setup.shapes.empty());
}

TEST(BuildWorld, ADefaultSceneMakesADefaultWorld) {
  const WorldSettings built = build_world(scene_without_ground({})).world->settings();
  const WorldSettings runtime;
  EXPECT_EQ(built.response, ResponseMode::kPlausible);
  EXPECT_EQ(built.response, runtime.response);
  EXPECT_EQ(built.gravity, runtime.gravity);
  EXPECT_EQ(built.paper_passes, runtime.paper_passes);
  EXPECT_EQ(built.collision_passes, runtime.collision_passes);
  EXPECT_EQ(built.solver.soft_substeps, runtime.solver.soft_substeps);
  EXPECT_EQ(built.solver.linear_slop, runtime.solver.linear_slop);
  EXPECT_EQ(built.solver.contacts, runtime.solver.contacts);
  EXPECT_EQ(built.solver.manifold_points, runtime.solver.manifold_points);
  EXPECT_EQ(built.sleep.enabled, runtime.sleep.enabled);
  EXPECT_EQ(built.sleep.time, runtime.sleep.time);
  EXPECT_EQ(built.ground_restitution, runtime.ground_restitution);
  EXPECT_EQ(built.ground_friction, runtime.ground_friction);
}

TEST(BuildWorld, WorldSettingsTheWorldRefusesAreReported) {
  Scene scene = scene_without_ground({});
  scene.collision_passes = 0;
  EXPECT_THROW((void)build_world(scene), Error);
  scene.collision_passes = 1;
  scene.solver.manifold_points = 9;
  EXPECT_THROW((void)build_world(scene), Error);
}

// The fastest upward speed of a box dropped onto a static box, whose pair has `material` if
// given (else the mix of their own restitutions, 0.3).
float rebound_speed(const test::TempDir& dir, std::optional<PairMaterial> material) {
  const auto box = dir.write("cube.obj", obj_text(make_box({1.0, 1.0, 1.0})));
  BodySpec floor = octree_body(box.string(), 2);
  floor.is_static = true;
  BodySpec falling = octree_body(box.string(), 2);
  falling.position = Vec3(0.0f, 1.5f, 0.0f);
  Scene scene = scene_without_ground({floor, falling});
  if (material) scene.pair_materials.push_back({.bodies = {1, 0}, .material = *material});
  const SimulationSetup setup = build_world(scene);
  float rebound = 0.0f;
  for (int frame = 0; frame < 60; ++frame) {
    (void)setup.world->step(1.0f / 60.0f);
    rebound = std::max(rebound, setup.world->body(setup.bodies[1]).linear_velocity.y());
  }
  return rebound;
}

TEST(BuildWorld, PairMaterialsReachTheWorld) {
  const test::TempDir dir;
  // The box lands at about 1.9 m/s, above the restitution threshold: a pair restitution of 1
  // sends it back up about as fast, their own 0.3 at about a third of that, 0 hardly at all.
  EXPECT_GT(rebound_speed(dir, PairMaterial{.friction = 0.5f, .restitution = 1.0f}), 1.5f);
  const float own = rebound_speed(dir, std::nullopt);
  EXPECT_GT(own, 0.3f);
  EXPECT_LT(own, 1.0f);
  EXPECT_LT(rebound_speed(dir, PairMaterial{.friction = 0.5f, .restitution = 0.0f}), 0.1f);
}

TEST(BuildWorld, APairMaterialTheWorldCannotTakeIsNamedByItsJsonPath) {
  Scene scene = scene_without_ground({octree_body("bunny", 1), octree_body("bunny", 1)});
  scene.pair_materials.push_back({.bodies = {0, 1}, .material = {}});
  scene.pair_materials.push_back({.bodies = {1, 2}, .material = {}});
  EXPECT_THAT(build_error(scene), HasSubstr("test scene: /pair_materials/1: no body 2"));
  scene.pair_materials[1] = {.bodies = {1, 0},
                             .material = {.friction = -1.0f, .restitution = 0.3f}};
  EXPECT_THAT(build_error(scene),
              AllOf(HasSubstr("test scene: /pair_materials/1: "), HasSubstr("friction")));
}

TEST(BuildWorld, ABodyThatCannotBeBuiltIsNamedByItsJsonPath) {
  const test::TempDir dir;
  const auto box = dir.write("box.obj", obj_text(make_box({1.0, 1.0, 1.0})));
  const std::string gone = (dir.path() / "gone.obj").string();
  const std::string missing =
      build_error(scene_without_ground({octree_body(box.string(), 1), octree_body(gone, 1)}));
  EXPECT_THAT(missing, HasSubstr("test scene: /bodies/1: "));
  EXPECT_THAT(missing, HasSubstr("gone.obj"));

  BodySpec massless = octree_body(box.string(), 1);
  massless.mass = -1.0;
  EXPECT_THAT(build_error(scene_without_ground(
                  {octree_body(box.string(), 1), octree_body(box.string(), 1), massless})),
              HasSubstr("/bodies/2: "));
}

TEST(BuildWorld, AMassMadeFromADensityIsHeldToTheMassRange) {
  // Each figure is in its range, their product is not: a 1 km bunny of 10⁶ kg/m³ weighs
  // 1.99e14 kg, a 1 mm bunny of 10⁻³ kg/m³ 1.99e-13 kg (the unit bunny encloses 0.199 m³).
  BodySpec heavy = octree_body("bunny", 1);
  heavy.size = 1000.0;
  heavy.density = 1e6;
  EXPECT_THAT(build_error(scene_without_ground({octree_body("bunny", 1), heavy})),
              HasSubstr("test scene: /bodies/1: density 1e+06 kg/m³ × volume 1.99e+08 m³ gives "
                        "a mass of 1.99e+14 kg; it must be between 1e-06 and 1e+09 kg"));
  BodySpec light = octree_body("bunny", 1);
  light.size = 0.001;
  light.density = 1e-3;
  EXPECT_THAT(build_error(scene_without_ground({light})),
              HasSubstr("/bodies/0: density 0.001 kg/m³ × volume 1.99e-10 m³ gives a mass of "
                        "1.99e-13 kg"));
  // A given mass at the range's ends is taken.
  heavy.mass = 1e9;
  light.mass = 1e-6;
  EXPECT_NO_THROW((void)build_world(scene_without_ground({heavy, light})));
}

// A bunny at each corner of the size and mass ranges (1 mm to 1 km, 1 mg to 10⁹ kg) dropped
// onto the plane from 0.4 of its size: in every response it stays finite (a float inverse of the
// corners' inertias made them NaN in the first step), and the plausible solvers keep it above the
// plane. Paper mode makes contacts from overlaps only: the 1 mm bunny, 2.7 mm per step after one
// step, passes through the plane as the paper's method lets it. (How far it sinks or where it
// rests is not asked: the solver's lengths, such as the 0.4 mm slop, are made for metre-sized
// bodies; docs/dynamics.md.)
TEST(BuildWorld, BodiesAtTheEndsOfTheRangesFallOntoThePlaneAndStayFinite) {
  for (const double size : {0.001, 1000.0}) {
    for (const double mass : {1e-6, 1e9}) {
      for (const ResponseMode mode : {ResponseMode::kPaper, ResponseMode::kPlausible}) {
        SCOPED_TRACE(testing::Message() << "size " << size << " m, mass " << mass << " kg, "
                                        << response_mode_name(mode));
        BodySpec bunny = octree_body("bunny", 2);
        bunny.size = size;
        bunny.mass = mass;
        bunny.position = Vec3(0.0f, static_cast<float>(0.4 * size), 0.0f);
        Scene scene = scene_without_ground({bunny});
        scene.ground.kind = GroundSpec::Kind::kPlane;
        scene.response = mode;
        const SimulationSetup setup = build_world(scene);
        for (int frame = 0; frame < 400; ++frame) {
          const StepStats& stats = setup.world->step(1.0f / 60.0f);
          ASSERT_FALSE(stats.non_finite_body.has_value()) << "frame " << frame;
          if (mode == ResponseMode::kPlausible) {
            ASSERT_GT(setup.world->body(setup.bodies[0]).pose.translation.y(), 0.0f)
                << "frame " << frame;
          }
        }
      }
    }
  }
}

// The ends of every range at once: a 1 km, 10⁹ kg bunny thrown down at 10⁴ m/s and spun at
// 10⁴ rad/s, 1 mm, 1 mg bunnies (one as fast), another 1 km bunny, 1 s steps under 1,000 m/s²
// of gravity. Nothing about it is plausible (a step carries a body 10 km, through the ground),
// but every response keeps it finite.
TEST(BuildWorld, MixedExtremesStayFinite) {
  const auto bunny = [](double size, double mass, Vec3 position) {
    BodySpec body = octree_body("bunny", 2);
    body.size = size;
    body.mass = mass;
    body.position = position;
    return body;
  };
  std::vector<BodySpec> bodies = {
      bunny(1000.0, 1e9, Vec3(0.0f, 2000.0f, 0.0f)), bunny(0.001, 1e-6, Vec3(0.0f, 1.0f, 0.0f)),
      bunny(0.001, 1e-6, Vec3(0.3f, 1.0f, 0.0f)), bunny(1000.0, 1e9, Vec3(100.0f, 500.0f, 0.0f))};
  bodies[0].linear_velocity = Vec3(0.0f, -1e4f, 0.0f);
  bodies[0].angular_velocity = Vec3(1e4f, 0.0f, 0.0f);
  bodies[1].linear_velocity = Vec3(1e4f, 0.0f, 0.0f);
  bodies[1].angular_velocity = Vec3(0.0f, 1e4f, 1e4f);
  for (const ResponseMode mode : {ResponseMode::kPaper, ResponseMode::kPlausible}) {
    SCOPED_TRACE(testing::Message() << response_mode_name(mode));
    Scene scene = scene_without_ground(bodies);
    scene.ground.kind = GroundSpec::Kind::kOctreeBox;
    scene.gravity = Vec3(0.0f, -1000.0f, 0.0f);
    scene.response = mode;
    const SimulationSetup setup = build_world(scene);
    for (int frame = 0; frame < 300; ++frame) {
      ASSERT_FALSE(setup.world->step(1.0f).non_finite_body.has_value()) << "frame " << frame;
    }
  }
}

TEST(BuildWorld, ProgressReachesOneOncePerBody) {
  const Scene scene = scene_without_ground(
      {octree_body("bunny", 1), octree_body("bunny", 1), octree_body("bunny", 1)});
  std::vector<double> reported;
  BuildWorldOptions options;
  options.progress = [&reported](double fraction) { reported.push_back(fraction); };
  (void)build_world(scene, options);
  ASSERT_EQ(reported.size(), 3u);
  EXPECT_DOUBLE_EQ(reported.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
}

TEST(BuildWorld, ABunnyDroppedOntoThePlaneStaysAboveIt) {
  BodySpec bunny = octree_body("bunny", 2);
  bunny.position = Vec3(0.0f, 1.0f, 0.0f);
  Scene scene = scene_without_ground({bunny});
  scene.ground.kind = GroundSpec::Kind::kPlane;
  BuildWorldOptions options;
  options.plausibility_figures = true;  // the penetration, checked below
  const SimulationSetup setup = build_world(scene, options);
  const float reach = static_cast<float>(setup.shapes[0].max_vertex_distance);
  float lowest = 1.0f;
  bool touched = false;
  for (int frame = 0; frame < 60; ++frame) {
    const StepStats& stats = setup.world->step(1.0f / 60.0f);
    ASSERT_FALSE(stats.non_finite_body.has_value()) << "frame " << frame;
    touched = touched || stats.contacts > 0;
    const float y = setup.world->body(setup.bodies[0]).pose.translation.y();
    lowest = std::min(lowest, y);
    // The centre of mass stays above the plane, and the body never sinks by more than a small
    // fraction of its size.
    ASSERT_GT(y, 0.0f) << "frame " << frame;
    EXPECT_LT(stats.deepest_penetration, 0.1f) << "frame " << frame;
  }
  // It fell far enough to reach the plane (the lowest point of the body is within `reach` of the
  // centre of mass) and came to rest on it rather than floating.
  EXPECT_TRUE(touched);
  EXPECT_LT(lowest, reach);
  const RigidBody& body = setup.world->body(setup.bodies[0]);
  EXPECT_LT(body.pose.translation.y(), reach);
  EXPECT_LT(body.linear_velocity.norm(), 1.0f);
}

}  // namespace
}  // namespace sphys::tools
