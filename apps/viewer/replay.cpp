#include "replay.h"

#include <string>

#include "sphys/error.h"
#include "sphys/tools/scene_file.h"

namespace sphys::viewer {

Replay::Replay(const std::filesystem::path& path, const tools::BuildWorldOptions& build)
    : recording_(tools::read_recording(path)) {
  try {
    scene_ = tools::parse_recorded_scene(recording_.metadata, path);
  } catch (const Error& error) {
    throw Error(path.string() + ": its scene cannot be read: " + error.what());
  }
  if (recording_.body_count != scene_.bodies.size()) {
    throw Error(path.string() + ": the recording has " + std::to_string(recording_.body_count) +
                " bodies but its scene " + std::to_string(scene_.bodies.size()));
  }
  if (recording_.frame_count == 0) throw Error(path.string() + ": the recording has no frames");
  setup_ = tools::build_world(scene_, build);
}

void Replay::bodies(std::uint32_t frame, std::vector<BodyView>& out) const {
  out.clear();
  const std::span<const tools::BodyPose> poses = recording_.frame(frame);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    out.push_back(
        {setup_.body_shape[i], Transform{poses[i].orientation, poses[i].position}, false});
  }
}

}  // namespace sphys::viewer
