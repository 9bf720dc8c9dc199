#include "sphys/tools/gltf_export.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <tiny_gltf.h>
#include <vector>

#include "io/atomic_file.h"
#include "sphys/error.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/scene_meshes.h"

namespace sphys::tools {
namespace {

// The plane drawn for an infinite ground plane: wide enough for any of the presets. unit: m
constexpr double kPlaneSize = 60.0;

// Builds the model's single buffer and the views and accessors into it.
class Builder {
 public:
  explicit Builder(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  // Floats as an accessor of `type` (TINYGLTF_TYPE_*), `width` floats per element; min and max
  // per component when `bounds` (glTF requires them for positions and animation inputs).
  int floats(const std::vector<float>& values, int type, int width, bool bounds, int target = 0) {
    const int view = add_view(values.data(), values.size() * sizeof(float), target);
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.count = values.size() / static_cast<std::size_t>(width);
    accessor.type = type;
    if (bounds) {
      accessor.minValues.assign(static_cast<std::size_t>(width),
                                std::numeric_limits<double>::infinity());
      accessor.maxValues.assign(static_cast<std::size_t>(width),
                                -std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t c = i % static_cast<std::size_t>(width);
        accessor.minValues[c] = std::min(accessor.minValues[c], static_cast<double>(values[i]));
        accessor.maxValues[c] = std::max(accessor.maxValues[c], static_cast<double>(values[i]));
      }
    }
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  int indices(const std::vector<std::uint32_t>& values) {
    const int view = add_view(values.data(), values.size() * sizeof(std::uint32_t),
                              TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.count = values.size();
    accessor.type = TINYGLTF_TYPE_SCALAR;
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size() - 1);
  }

 private:
  int add_view(const void* data, std::size_t bytes, int target) {
    std::vector<unsigned char>& buffer = model_.buffers[0].data;
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);  // every view starts 4-byte aligned
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    buffer.resize(buffer.size() + bytes);
    std::memcpy(buffer.data() + view.byteOffset, data, bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size() - 1);
  }

  tinygltf::Model& model_;
};

int add_material(tinygltf::Model& model, const std::string& name, double r, double g, double b) {
  tinygltf::Material material;
  material.name = name;
  material.pbrMetallicRoughness.baseColorFactor = {r, g, b, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  model.materials.push_back(material);
  return static_cast<int>(model.materials.size() - 1);
}

// A mesh with positions, smooth normals (area-weighted over the triangles at a vertex) and
// indices.
int add_mesh(tinygltf::Model& model, Builder& builder, const TriangleMesh& mesh,
             const std::string& name, int material) {
  const std::vector<Vec3d> normals = vertex_normals(mesh);
  std::vector<float> positions;
  std::vector<float> normal_values;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      positions.push_back(static_cast<float>(mesh.vertices[v][c]));
      normal_values.push_back(static_cast<float>(normals[v][c]));
    }
  }
  std::vector<std::uint32_t> indices;
  for (const Triangle& triangle : mesh.triangles) {
    indices.insert(indices.end(), triangle.begin(), triangle.end());
  }
  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] =
      builder.floats(positions, TINYGLTF_TYPE_VEC3, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
  primitive.attributes["NORMAL"] =
      builder.floats(normal_values, TINYGLTF_TYPE_VEC3, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  primitive.indices = builder.indices(indices);
  primitive.material = material;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = name;
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);
  return static_cast<int>(model.meshes.size() - 1);
}

std::vector<std::uint32_t> exported_frames(const Recording& recording,
                                           const GltfExportOptions& options) {
  if (recording.frame_count == 0) throw Error("the recording has no frames");
  if (options.every == 0) throw Error("--every must be at least 1");
  const std::uint32_t last = options.last.value_or(recording.frame_count - 1);
  if (last >= recording.frame_count || options.first > last) {
    throw Error("frames " + std::to_string(options.first) + " to " + std::to_string(last) +
                " are not in the recording, which has frames 0 to " +
                std::to_string(recording.frame_count - 1));
  }
  std::vector<std::uint32_t> frames;
  for (std::uint64_t f = options.first; f <= last; f += options.every) {
    frames.push_back(static_cast<std::uint32_t>(f));
  }
  return frames;
}

void add_animation(tinygltf::Model& model, Builder& builder, const Recording& recording,
                   const std::vector<std::uint32_t>& frames) {
  std::vector<float> times;
  for (const std::uint32_t f : frames) {
    times.push_back(static_cast<float>((f - frames.front()) * recording.time_step));
  }
  const int input = builder.floats(times, TINYGLTF_TYPE_SCALAR, 1, true);
  tinygltf::Animation animation;
  animation.name = "simulation";
  for (std::uint32_t body = 0; body < recording.body_count; ++body) {
    // Each body's track is a pass over every frame: a long export stops here on Ctrl-C.
    throw_if_interrupted();
    std::vector<float> translations;
    std::vector<float> rotations;
    Quat previous = recording.frame(frames.front())[body].orientation;
    for (const std::uint32_t f : frames) {
      const BodyPose& pose = recording.frame(f)[body];
      translations.insert(translations.end(),
                          {pose.position.x(), pose.position.y(), pose.position.z()});
      // q and -q are the same turn; glTF interpolates the stored values, so keep neighbours on
      // the same side to turn the short way.
      Quat q = pose.orientation;
      if (q.coeffs().dot(previous.coeffs()) < 0.0f) q.coeffs() = -q.coeffs();
      previous = q;
      rotations.insert(rotations.end(), {q.x(), q.y(), q.z(), q.w()});  // glTF order: x y z w
    }
    const auto channel = [&](const std::vector<float>& values, int type, int width,
                             const char* path) {
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.output = builder.floats(values, type, width, false);
      sampler.interpolation = "LINEAR";
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel target;
      target.sampler = static_cast<int>(animation.samplers.size() - 1);
      target.target_node = static_cast<int>(body);
      target.target_path = path;
      animation.channels.push_back(target);
    };
    channel(translations, TINYGLTF_TYPE_VEC3, 3, "translation");
    channel(rotations, TINYGLTF_TYPE_VEC4, 4, "rotation");
  }
  model.animations.push_back(animation);
}

}  // namespace

GltfExportSummary write_gltf(const std::filesystem::path& path, const Recording& recording,
                             const Scene& scene, const GltfExportOptions& options,
                             std::span<const std::shared_ptr<const TriangleMesh>> robot_meshes) {
  if (recording.body_count != scene.bodies.size() + robot_meshes.size()) {
    throw Error("the recording has " + std::to_string(recording.body_count) +
                " bodies but its scene " + std::to_string(scene.bodies.size()) +
                (robot_meshes.empty() ? std::string()
                                      : " and its robots " + std::to_string(robot_meshes.size())));
  }
  const std::vector<std::uint32_t> frames = exported_frames(recording, options);
  SceneMeshes meshes = scene_meshes(scene);
  for (const std::shared_ptr<const TriangleMesh>& mesh : robot_meshes) {
    meshes.body_shape.push_back(static_cast<std::uint32_t>(meshes.shapes.size()));
    meshes.shapes.push_back(mesh);
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "sphys";
  Builder builder(model);
  const int body_material = add_material(model, "body", 0.85, 0.72, 0.55);
  for (std::size_t s = 0; s < meshes.shapes.size(); ++s) {
    add_mesh(model, builder, *meshes.shapes[s], "shape " + std::to_string(s), body_material);
  }
  tinygltf::Scene gltf_scene;
  const std::span<const BodyPose> start = recording.frame(frames.front());
  for (std::uint32_t body = 0; body < recording.body_count; ++body) {
    tinygltf::Node node;
    node.name = "body " + std::to_string(body);
    node.mesh = static_cast<int>(meshes.body_shape[body]);
    const BodyPose& pose = start[body];
    node.translation = {pose.position.x(), pose.position.y(), pose.position.z()};
    node.rotation = {pose.orientation.x(), pose.orientation.y(), pose.orientation.z(),
                     pose.orientation.w()};
    model.nodes.push_back(node);
    gltf_scene.nodes.push_back(static_cast<int>(body));
  }
  const TriangleMesh ground = ground_mesh(scene.ground, kPlaneSize);
  if (!ground.triangles.empty()) {
    tinygltf::Node node;
    node.name = "ground";
    node.mesh =
        add_mesh(model, builder, ground, "ground", add_material(model, "ground", 0.5, 0.5, 0.5));
    model.nodes.push_back(node);
    gltf_scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }
  model.scenes.push_back(gltf_scene);
  model.defaultScene = 0;
  if (frames.size() > 1) add_animation(model, builder, recording, frames);

  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, false, true)) {
    throw Error(path.string() + ": cannot encode the glTF");
  }
  const std::string data = bytes.str();
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
  });
  return {static_cast<std::uint32_t>(frames.size()), recording.body_count,
          static_cast<std::uint32_t>(meshes.shapes.size()), data.size()};
}

}  // namespace sphys::tools
