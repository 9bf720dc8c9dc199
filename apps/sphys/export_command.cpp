#include <charconv>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "sphys/error.h"
#include "sphys/tools/gltf_export.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"

namespace sphys::cli {
namespace {

namespace fs = std::filesystem;

struct ExportOptions {
  std::string recording;
  std::string gltf;
  std::optional<std::string> frames;
  std::uint32_t every = 1;
};

std::uint32_t frame_number(std::string_view text, const std::string& option) {
  std::uint32_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw Error("--frames: expected FIRST:LAST with frame numbers from 0, got '" + option + "'");
  }
  return value;
}

// "A:B", "A:" or ":B" (frames from 0, both ends included).
void read_frames(const std::string& text, tools::GltfExportOptions& options) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) {
    throw Error("--frames: expected FIRST:LAST with frame numbers from 0, got '" + text + "'");
  }
  const std::string_view first = std::string_view(text).substr(0, colon);
  const std::string_view last = std::string_view(text).substr(colon + 1);
  if (!first.empty()) options.first = frame_number(first, text);
  if (!last.empty()) options.last = frame_number(last, text);
}

// The meshes of the recording's robots' bodies, when it keeps them (recording_keeps_robots),
// from a world made for them alone.
std::vector<std::shared_ptr<const tools::TriangleMesh>> robot_meshes(
    const tools::Scene& scene, const tools::Recording& recording) {
  if (scene.robots.empty()) return {};
  World world(tools::world_settings(scene));
  const tools::SceneRobots robots = tools::add_scene_robots(scene, world);
  if (!tools::recording_keeps_robots(scene, robots, recording.body_count)) return {};
  std::vector<std::shared_ptr<const tools::TriangleMesh>> meshes;
  for (const tools::BodyShape& shape : robots.shapes) meshes.push_back(shape.body_mesh);
  return meshes;
}

void run(const ExportOptions& options) {
  tools::catch_interruptions();
  tools::GltfExportOptions gltf;
  if (options.frames) read_frames(*options.frames, gltf);
  gltf.every = options.every;
  const fs::path recording_path(options.recording);
  const tools::Recording recording = tools::read_recording(recording_path);
  tools::throw_if_interrupted();
  tools::Scene scene;
  try {
    scene = tools::parse_recorded_scene(recording.metadata, recording_path);
  } catch (const Error& error) {
    throw Error(recording_path.string() + ": its scene cannot be read: " + error.what());
  }
  tools::GltfExportSummary summary;
  try {
    summary =
        tools::write_gltf(options.gltf, recording, scene, gltf, robot_meshes(scene, recording));
  } catch (const Error& error) {
    throw Error(recording_path.string() + ": " + error.what());
  }
  std::printf("wrote %s: %u bodies (%u distinct meshes), %u frames, %.1f MB\n",
              options.gltf.c_str(), summary.bodies, summary.meshes, summary.frames,
              static_cast<double>(summary.bytes) / 1e6);
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Write a recording of sphys simulate as glTF 2.0 (meshes and their animation)");
  cmd->add_option("recording", options->recording, "The .sphysrec file")
      ->check(kFileName)
      ->required();
  cmd->add_option("--gltf", options->gltf, "The .glb file to write")->check(kFileName)->required();
  cmd->add_option("--frames", options->frames,
                  "FIRST:LAST, frames from 0, both included (either may be left out)");
  cmd->add_option("--every", options->every, "Keep every Nth frame of those")
      ->capture_default_str();
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
