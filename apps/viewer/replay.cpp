#include "replay.h"

#include <string>

#include "sphys/error.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/scene_robots.h"

namespace sphys::viewer {

Replay::Replay(const std::filesystem::path& path, const tools::BuildWorldOptions& build)
    : recording_(tools::read_recording(path)) {
  try {
    scene_ = tools::parse_recorded_scene(recording_.metadata, path);
  } catch (const Error& error) {
    throw Error(path.string() + ": its scene cannot be read: " + error.what());
  }
  if (recording_.frame_count == 0) throw Error(path.string() + ": the recording has no frames");
  // The world is made for the shapes alone: it is never stepped.
  tools::SimulationSetup setup = tools::build_world(scene_, build);
  const tools::SceneRobots robots = tools::add_scene_robots(scene_, *setup.world);
  bool keeps_robots = false;
  try {
    keeps_robots = tools::recording_keeps_robots(scene_, robots, recording_.body_count);
  } catch (const Error& error) {
    throw Error(path.string() + ": " + error.what());
  }
  shapes_ = setup.shapes;
  body_shape_ = setup.body_shape;
  if (keeps_robots) {
    for (const tools::BodyShape& shape : robots.shapes) {
      body_shape_.push_back(static_cast<std::uint32_t>(shapes_.size()));
      shapes_.push_back(shape);
    }
  }
}

void Replay::bodies(std::uint32_t frame, std::vector<BodyView>& out) const {
  out.clear();
  const std::span<const tools::BodyPose> poses = recording_.frame(frame);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    out.push_back({body_shape_[i], Transform{poses[i].orientation, poses[i].position}, false});
  }
}

}  // namespace sphys::viewer
