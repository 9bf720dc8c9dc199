#include "sphys/tools/gltf_export.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <tiny_gltf.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// A 2 × 1 × 1 box as OFF: 8 corners, 12 triangles.
constexpr const char* kBoxOff = R"(OFF
8 12 0
-1 -0.5 -0.5
1 -0.5 -0.5
-1 0.5 -0.5
1 0.5 -0.5
-1 -0.5 0.5
1 -0.5 0.5
-1 0.5 0.5
1 0.5 0.5
3 0 4 6
3 0 6 2
3 1 3 7
3 1 7 5
3 0 1 5
3 0 5 4
3 2 6 7
3 2 7 3
3 0 2 3
3 0 3 1
3 4 5 7
3 4 7 6
)";

// Two boxes (one mesh) over the exact plane, and a recording of `frames` frames in which body 0
// rises by 0.1 m a frame and body 1 turns about y by 0.1 rad a frame.
struct Fixture {
  test::TempDir dir;
  Scene scene;
  Recording recording;

  explicit Fixture(std::uint32_t frames) {
    scene.name = "boxes.json";
    BodySpec body;
    body.mesh = dir.write("box.off", kBoxOff).string();
    body.size.reset();  // as given: 2 m long
    scene.bodies = {body, body};
    scene.ground.kind = GroundSpec::Kind::kPlane;
    recording.time_step = 0.05;
    recording.body_count = 2;
    recording.frame_count = frames;
    for (std::uint32_t f = 0; f < frames; ++f) {
      recording.poses.push_back(
          {Vec3(0.0f, 1.0f + 0.1f * static_cast<float>(f), 0.0f), Quat::Identity()});
      recording.poses.push_back(
          {Vec3(3.0f, 1.0f, 0.0f),
           Quat(Eigen::AngleAxisf(0.1f * static_cast<float>(f), Vec3::UnitY()))});
    }
  }
};

tinygltf::Model load(const fs::path& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error;
  std::string warning;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, path.string())) << error;
  return model;
}

// Accessor `index` as floats, as stored.
std::vector<float> floats(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& accessor = model.accessors[static_cast<std::size_t>(index)];
  const tinygltf::BufferView& view =
      model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  const std::size_t width =
      accessor.type == TINYGLTF_TYPE_SCALAR ? 1 : static_cast<std::size_t>(accessor.type);
  std::vector<float> values(accessor.count * width);
  std::memcpy(values.data(), model.buffers[0].data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(float));
  return values;
}

TEST(GltfExport, NodesMeshesAndTheAnimationFollowTheRecording) {
  const Fixture fixture(11);
  const fs::path out = fixture.dir.path() / "boxes.glb";
  const GltfExportSummary summary = write_gltf(out, fixture.recording, fixture.scene);
  EXPECT_EQ(summary.frames, 11u);
  EXPECT_EQ(summary.bodies, 2u);
  EXPECT_EQ(summary.meshes, 1u);
  EXPECT_EQ(summary.bytes, fs::file_size(out));

  const tinygltf::Model model = load(out);
  // Two bodies sharing the box mesh, then the ground.
  ASSERT_EQ(model.nodes.size(), 3u);
  EXPECT_EQ(model.nodes[0].mesh, model.nodes[1].mesh);
  ASSERT_EQ(model.meshes.size(), 2u);
  const tinygltf::Primitive& box = model.meshes[0].primitives.at(0);
  const tinygltf::Accessor& positions =
      model.accessors[static_cast<std::size_t>(box.attributes.at("POSITION"))];
  EXPECT_EQ(positions.count, 8u);
  EXPECT_EQ(model.accessors[static_cast<std::size_t>(box.indices)].count, 36u);
  // The box in its body frame: its centre of mass at the origin, 2 × 1 × 1.
  ASSERT_EQ(positions.minValues.size(), 3u);
  EXPECT_NEAR(positions.minValues[0], -1.0, 1e-6);
  EXPECT_NEAR(positions.maxValues[0], 1.0, 1e-6);
  EXPECT_NEAR(positions.maxValues[1], 0.5, 1e-6);
  // The first frame's poses on the nodes.
  EXPECT_EQ(model.nodes[0].translation, (std::vector<double>{0.0, 1.0, 0.0}));
  EXPECT_EQ(model.nodes[1].translation, (std::vector<double>{3.0, 1.0, 0.0}));

  ASSERT_EQ(model.animations.size(), 1u);
  const tinygltf::Animation& animation = model.animations[0];
  ASSERT_EQ(animation.channels.size(), 4u);
  const tinygltf::AnimationSampler& rise =
      animation.samplers[static_cast<std::size_t>(animation.channels[0].sampler)];
  EXPECT_EQ(animation.channels[0].target_node, 0);
  EXPECT_EQ(animation.channels[0].target_path, "translation");
  const std::vector<float> times = floats(model, rise.input);
  ASSERT_EQ(times.size(), 11u);
  EXPECT_FLOAT_EQ(times[10], 0.5f);
  const std::vector<float> heights = floats(model, rise.output);
  EXPECT_FLOAT_EQ(heights[3 * 10 + 1], 2.0f);
  // Body 1's turn, as (x, y, z, w): half the angle in y and w.
  const tinygltf::AnimationSampler& turn =
      animation.samplers[static_cast<std::size_t>(animation.channels[3].sampler)];
  EXPECT_EQ(animation.channels[3].target_path, "rotation");
  const std::vector<float> rotations = floats(model, turn.output);
  EXPECT_NEAR(rotations[4 * 10 + 1], std::sin(0.5f), 1e-6f);
  EXPECT_NEAR(rotations[4 * 10 + 3], std::cos(0.5f), 1e-6f);
}

TEST(GltfExport, FramesAndEveryThinTheAnimation) {
  const Fixture fixture(11);
  const fs::path out = fixture.dir.path() / "thin.glb";
  EXPECT_EQ(
      write_gltf(out, fixture.recording, fixture.scene, {.first = 2, .last = 8, .every = 3}).frames,
      3u);
  const tinygltf::Model model = load(out);
  // Frames 2, 5 and 8: times from the first exported frame.
  const std::vector<float> times = floats(model, model.animations[0].samplers[0].input);
  ASSERT_EQ(times.size(), 3u);
  EXPECT_FLOAT_EQ(times[1], 0.15f);
  EXPECT_FLOAT_EQ(times[2], 0.3f);
  EXPECT_NEAR(model.nodes[0].translation[1], 1.2, 1e-6);
  // One frame: a still scene with no animation.
  const fs::path still = fixture.dir.path() / "still.glb";
  EXPECT_EQ(write_gltf(still, fixture.recording, fixture.scene, {.first = 4, .last = 4}).frames,
            1u);
  EXPECT_TRUE(load(still).animations.empty());
}

TEST(GltfExport, QuaternionsKeepToOneSideSoTheTurnIsShort) {
  Fixture fixture(2);
  // The same turn written as q and then -q: stored on the same side, so glTF's interpolation
  // does not spin the body the long way round between them.
  fixture.recording.poses[3].orientation.coeffs() =
      -fixture.recording.poses[1].orientation.coeffs();
  const fs::path out = fixture.dir.path() / "flip.glb";
  (void)write_gltf(out, fixture.recording, fixture.scene);
  const tinygltf::Model model = load(out);
  const std::vector<float> rotations = floats(model, model.animations[0].samplers[3].output);
  EXPECT_EQ(rotations[3], rotations[7]);  // w of both frames, same sign
}

TEST(GltfExport, BadRequestsAreRefusedAndWriteNothing) {
  const Fixture fixture(5);
  const fs::path out = fixture.dir.path() / "bad.glb";
  const auto refused = [&](const GltfExportOptions& options, const std::string& message) {
    try {
      (void)write_gltf(out, fixture.recording, fixture.scene, options);
      ADD_FAILURE() << "no error for: " << message;
    } catch (const Error& error) {
      EXPECT_THAT(error.what(), HasSubstr(message));
    }
    EXPECT_FALSE(fs::exists(out));
  };
  refused({.first = 5, .last = std::nullopt, .every = 1},
          "frames 5 to 4 are not in the recording, which has frames 0 to 4");
  refused({.first = 0, .last = 9}, "frames 0 to 9 are not in the recording");
  refused({.first = 3, .last = 1}, "frames 3 to 1 are not in the recording");
  refused({.first = 0, .last = std::nullopt, .every = 0}, "--every must be at least 1");

  Scene three = fixture.scene;
  three.bodies.push_back(three.bodies.front());
  EXPECT_THROW((void)write_gltf(out, fixture.recording, three), Error);
  Scene missing = fixture.scene;
  missing.bodies[1].mesh = (fixture.dir.path() / "gone.off").string();
  try {
    (void)write_gltf(out, fixture.recording, missing);
    ADD_FAILURE() << "a missing mesh was not refused";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("boxes.json: /bodies/1: "));
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace sphys::tools
