#include "sphys/tools/build_world.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include "sphys/error.h"
#include "sphys/tools/ground.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/scene_meshes.h"
#include "sphys/tools/sph_file.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::tools {
namespace {

// What makes two bodies share a shape: the same mesh at the same size with the same tree.
using ShapeKey = std::tuple<std::string, std::size_t, double, std::string, int, int, int>;

ShapeKey shape_key(const BodySpec& body, const TreeSpec& tree) {
  return {body.mesh,
          body.triangles.value_or(0),
          body.size.value_or(0.0),
          tree.sph_file ? tree.sph_file->string() : std::string(),
          static_cast<int>(tree.method),
          tree.branching,
          tree.depth};
}

std::filesystem::path resolve(const Scene& scene, const std::filesystem::path& path) {
  return path.is_absolute() || scene.base_directory.empty() ? path : scene.base_directory / path;
}

std::shared_ptr<const SphereTree> body_tree(const Scene& scene, const TriangleMesh& mesh,
                                            const TreeSpec& spec, const BuildWorldOptions& options,
                                            std::string& source) {
  if (spec.sph_file) {
    const std::filesystem::path path = resolve(scene, *spec.sph_file);
    SphereTree tree = read_sph(path);
    source = path.string();
    if (options.tree_depth && *options.tree_depth < tree.depth()) {
      tree = tree.truncated(*options.tree_depth);
      source += ", cut to depth " + std::to_string(*options.tree_depth);
    }
    return std::make_shared<const SphereTree>(std::move(tree));
  }
  BuildOptions build;
  build.method = spec.method;
  build.branching = spec.branching;
  build.depth = spec.depth;
  source = std::string(method_name(spec.method)) + ", branching " + std::to_string(spec.branching) +
           ", depth " + std::to_string(spec.depth);
  return std::make_shared<const SphereTree>(
      build_sphere_tree_cached(mesh, build, options.cache_dir).tree);
}

double max_vertex_distance(const TriangleMesh& mesh) {
  double distance = 0.0;
  for (const Vec3d& vertex : mesh.vertices) distance = std::max(distance, vertex.norm());
  return distance;
}

BodyShape make_shape(const Scene& scene, const BodySpec& body, const TreeSpec& tree,
                     const BuildWorldOptions& options) {
  BodyShape shape;
  shape.mesh = body.mesh;
  auto mesh = std::make_shared<TriangleMesh>(body_frame_mesh(scene, body));
  shape.volume = compute_mass_properties(*mesh, {.density = 1.0}).volume;
  shape.tree = body_tree(scene, *mesh, tree, options, shape.tree_source);
  shape.max_vertex_distance = max_vertex_distance(*mesh);
  shape.body_mesh = std::move(mesh);
  return shape;
}

// The world with its ground: the detector's plane or a static octree body.
void make_world(const Scene& scene, const BuildWorldOptions& options, SimulationSetup& setup) {
  WorldSettings settings = world_settings(scene);
  settings.threads = options.threads;
  settings.plausibility_figures = options.plausibility_figures;
  settings.broad_phase = options.broad_phase;
  const GroundSpec& ground = scene.ground;
  switch (ground.kind) {
    case GroundSpec::Kind::kNone:
      setup.world = std::make_unique<World>(settings);
      return;
    case GroundSpec::Kind::kPlane:
      settings.collision.ground_plane_height = static_cast<float>(ground.height);
      setup.world = std::make_unique<World>(settings);
      return;
    case GroundSpec::Kind::kOctreeBox: {
      setup.world = std::make_unique<World>(settings);
      BodyDesc desc;
      desc.tree = std::make_shared<const SphereTree>(build_ground_tree(
          {.size = ground.size, .thickness = ground.thickness, .depth = ground.depth}));
      desc.pose.translation = Vec3(0.0f, static_cast<float>(ground.height), 0.0f);
      desc.restitution = ground.restitution;
      desc.friction = ground.friction;
      desc.is_static = true;
      setup.ground = setup.world->add_body(desc);
      setup.ground_tree = desc.tree;
      return;
    }
  }
}

// Scene body indices to the world's bodies. A scene made in code may name a body it lacks or a
// material the world refuses; the message names the pair's JSON path, as for a body.
void set_pair_materials(const Scene& scene, const SimulationSetup& setup) {
  for (std::size_t k = 0; k < scene.pair_materials.size(); ++k) {
    const PairMaterialSpec& pair = scene.pair_materials[k];
    const std::string where = scene.name + ": /pair_materials/" + std::to_string(k) + ": ";
    for (const std::size_t index : pair.bodies) {
      if (index >= setup.bodies.size()) throw Error(where + "no body " + std::to_string(index));
    }
    try {
      setup.world->set_pair_material(setup.bodies[pair.bodies[0]], setup.bodies[pair.bodies[1]],
                                     pair.material);
    } catch (const Error& error) {
      throw Error(where + error.what());
    }
  }
}

// The joints after every body, in the scene's order; as for a pair, a scene made in code may name
// a body it lacks or a joint the world refuses (paper mode), and the message names the JSON path.
void add_joints(const Scene& scene, const SimulationSetup& setup) {
  for (std::size_t k = 0; k < scene.joints.size(); ++k) {
    const JointSpec& joint = scene.joints[k];
    const std::string where = scene.name + ": /joints/" + std::to_string(k) + ": ";
    const auto body_id = [&](const std::optional<std::size_t>& index) {
      if (!index) return BodyId{};
      if (*index >= setup.bodies.size()) throw Error(where + "no body " + std::to_string(*index));
      return setup.bodies[*index];
    };
    JointDesc desc = joint.desc;
    desc.body_a = body_id(joint.body_a);
    desc.body_b = body_id(joint.body_b);
    try {
      (void)setup.world->add_joint(desc);
    } catch (const Error& error) {
      throw Error(where + error.what());
    }
  }
}

}  // namespace

SimulationSetup build_world(const Scene& scene, const BuildWorldOptions& options) {
  if (options.tree_depth && (*options.tree_depth < 1 || *options.tree_depth > 6)) {
    throw Error("the sphere-tree depth must be 1 to 6, got " + std::to_string(*options.tree_depth));
  }
  SimulationSetup setup;
  make_world(scene, options, setup);

  std::map<ShapeKey, std::uint32_t> shape_of_key;
  std::vector<MassProperties> unit_density;  // per shape, at density 1
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& body = scene.bodies[i];
    const std::string where = "/bodies/" + std::to_string(i);
    try {
      TreeSpec tree = body.tree;
      if (options.tree_depth && !tree.sph_file) tree.depth = *options.tree_depth;
      const ShapeKey key = shape_key(body, tree);
      auto found = shape_of_key.find(key);
      if (found == shape_of_key.end()) {
        setup.shapes.push_back(make_shape(scene, body, tree, options));
        unit_density.push_back(
            compute_mass_properties(*setup.shapes.back().body_mesh, {.density = 1.0}));
        found =
            shape_of_key.emplace(key, static_cast<std::uint32_t>(setup.shapes.size() - 1)).first;
      }
      const BodyShape& shape = setup.shapes[found->second];
      const MassProperties& unit = unit_density[found->second];
      const double mass = body.mass.value_or(body.density * unit.volume);
      if (mass < kMinBodyMass || mass > kMaxBodyMass) {
        char text[200];
        std::snprintf(text, sizeof text,
                      "density %.3g kg/m³ × volume %.3g m³ gives a mass of %.3g kg; it must be "
                      "between %g and %g kg (give a mass, or another density or size)",
                      body.density, unit.volume, mass, kMinBodyMass, kMaxBodyMass);
        throw Error(text);
      }

      BodyDesc desc;
      desc.tree = shape.tree;
      desc.pose.translation = body.position;
      desc.pose.rotation = body.orientation;
      desc.linear_velocity = body.linear_velocity;
      desc.angular_velocity = body.angular_velocity;
      desc.mass = static_cast<float>(mass);
      desc.inertia = (unit.inertia * (mass / unit.volume)).cast<float>();
      desc.restitution = body.restitution;
      desc.friction = body.friction;
      desc.is_static = body.is_static;
      setup.bodies.push_back(setup.world->add_body(desc));
      setup.body_shape.push_back(found->second);
    } catch (const Error& error) {
      throw Error(scene.name + ": " + where + ": " + error.what());
    }
    if (options.progress) {
      options.progress(static_cast<double>(i + 1) / static_cast<double>(scene.bodies.size()));
    }
  }
  set_pair_materials(scene, setup);
  add_joints(scene, setup);
  return setup;
}

}  // namespace sphys::tools
