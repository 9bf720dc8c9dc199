#pragma once

// A recording written by `sphys simulate --record`, played back: the scene it stores gives the
// meshes and sphere-trees of its bodies and robots, the recording the poses of every frame.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "body_view.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"

namespace sphys::viewer {

class Replay {
 public:
  // Throws sphys::Error naming the file for a recording that cannot be read, whose scene cannot
  // be read or built, or whose body count is neither its scene's bodies and robots' bodies nor,
  // as recordings made before robots were recorded, its scene's bodies alone.
  Replay(const std::filesystem::path& path, const tools::BuildWorldOptions& build);

  [[nodiscard]] std::uint32_t frame_count() const { return recording_.frame_count; }
  [[nodiscard]] double time_step() const { return recording_.time_step; }
  [[nodiscard]] const tools::Scene& scene() const { return scene_; }
  // The scene's bodies' shapes, then its robots' bodies'.
  [[nodiscard]] const std::vector<tools::BodyShape>& shapes() const { return shapes_; }
  // The recording's joints, their bodies indices into bodies().
  [[nodiscard]] const std::vector<tools::RecordedJoint>& joints() const {
    return recording_.joints;
  }
  // The bodies at frame `frame` (0 .. frame_count - 1): the scene's in its order, then its
  // robots'.
  void bodies(std::uint32_t frame, std::vector<BodyView>& out) const;

 private:
  tools::Recording recording_;
  tools::Scene scene_;
  std::vector<tools::BodyShape> shapes_;
  std::vector<std::uint32_t> body_shape_;  // index into shapes_, per recorded body
};

}  // namespace sphys::viewer
