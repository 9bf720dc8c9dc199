#include "sphys/tools/scene_meshes.h"

#include <map>
#include <string>
#include <tuple>

#include "sphys/error.h"
#include "sphys/tools/mass_properties.h"
#include "sphys/tools/model.h"
#include "sphys/tools/normalize.h"
#include "sphys/tools/primitives.h"

namespace sphys::tools {

TriangleMesh body_frame_mesh(const Scene& scene, const BodySpec& body) {
  const bool relative = !std::filesystem::path(body.mesh).is_absolute();
  const std::string source = body.mesh == kBunnyName || !relative || scene.base_directory.empty()
                                 ? body.mesh
                                 : (scene.base_directory / body.mesh).string();
  TriangleMesh mesh = load_model(source, body.triangles);
  if (body.size) return normalize(mesh, *body.size).mesh;
  const Vec3d center = compute_mass_properties(mesh).center_of_mass;
  for (Vec3d& vertex : mesh.vertices) vertex -= center;
  return mesh;
}

SceneMeshes scene_meshes(const Scene& scene) {
  // Bodies with the same mesh at the same size look the same.
  using MeshKey = std::tuple<std::string, std::size_t, double>;
  std::map<MeshKey, std::uint32_t> shape_of_key;
  SceneMeshes meshes;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& body = scene.bodies[i];
    const MeshKey key{body.mesh, body.triangles.value_or(0), body.size.value_or(0.0)};
    auto found = shape_of_key.find(key);
    if (found == shape_of_key.end()) {
      try {
        meshes.shapes.push_back(std::make_shared<const TriangleMesh>(body_frame_mesh(scene, body)));
      } catch (const Error& error) {
        throw Error(scene.name + ": /bodies/" + std::to_string(i) + ": " + error.what());
      }
      found = shape_of_key.emplace(key, static_cast<std::uint32_t>(meshes.shapes.size() - 1)).first;
    }
    meshes.body_shape.push_back(found->second);
  }
  return meshes;
}

TriangleMesh ground_mesh(const GroundSpec& ground, double plane_size) {
  TriangleMesh mesh;
  switch (ground.kind) {
    case GroundSpec::Kind::kNone:
      break;
    case GroundSpec::Kind::kPlane: {
      const double half = plane_size / 2.0;
      mesh.vertices = {Vec3d(-half, ground.height, -half), Vec3d(half, ground.height, -half),
                       Vec3d(half, ground.height, half), Vec3d(-half, ground.height, half)};
      // Counter-clockwise seen from above: the normal points up.
      mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
      break;
    }
    case GroundSpec::Kind::kOctreeBox: {
      mesh = make_box(Vec3d(ground.size, ground.thickness, ground.size));
      // make_box is centred on the origin; the ground's top face is at its height.
      const Vec3d shift(0.0, ground.height - ground.thickness / 2.0, 0.0);
      for (Vec3d& vertex : mesh.vertices) vertex += shift;
      break;
    }
  }
  mesh.name = "ground";
  return mesh;
}

}  // namespace sphys::tools
