#pragma once

// A recording written by `sphys simulate --record`, played back: the scene it stores gives the
// meshes and sphere-trees, the recording the poses of every frame.

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
  // be read or built, or whose body count is not its scene's.
  Replay(const std::filesystem::path& path, const tools::BuildWorldOptions& build);

  [[nodiscard]] std::uint32_t frame_count() const { return recording_.frame_count; }
  [[nodiscard]] double time_step() const { return recording_.time_step; }
  [[nodiscard]] const tools::Scene& scene() const { return scene_; }
  [[nodiscard]] const std::vector<tools::BodyShape>& shapes() const { return setup_.shapes; }
  // The recording's joints, their bodies indices into bodies().
  [[nodiscard]] const std::vector<tools::RecordedJoint>& joints() const {
    return recording_.joints;
  }
  // The bodies at frame `frame` (0 .. frame_count - 1), in the scene's order.
  void bodies(std::uint32_t frame, std::vector<BodyView>& out) const;

 private:
  tools::Recording recording_;
  tools::Scene scene_;
  tools::SimulationSetup setup_;  // for its shapes; its world is never stepped
};

}  // namespace sphys::viewer
