#pragma once

// The scene the window runs live: its world with its robots, stepped one frame at a time, reset to
// the start, with bodies dropped or shot in and the time-critical budget changed as it runs.

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "body_view.h"
#include "sphys/tools/build_world.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"

namespace sphys::viewer {

class LiveSimulation {
 public:
  // Builds the scene's world. Throws sphys::Error for a scene that cannot be built.
  LiveSimulation(tools::Scene scene, tools::BuildWorldOptions build);

  // Back to the scene's start: added bodies go, the detection budget stays.
  void reset();
  // One frame: the world steps by the scene's time step.
  const StepStats& step();

  [[nodiscard]] int frame() const { return frame_; }
  [[nodiscard]] const tools::Scene& scene() const { return scene_; }
  // The scene's bodies' shapes, then its robots' bodies'.
  [[nodiscard]] const std::vector<tools::BodyShape>& shapes() const { return shapes_; }
  [[nodiscard]] const World& world() const { return *setup_.world; }
  [[nodiscard]] std::size_t body_count() const { return bodies_.size(); }
  // The bodies as they are now: the scene's, its robots', then those added.
  void bodies(std::vector<BodyView>& out) const;
  // The scene's joints and its robots', their bodies indices into bodies().
  [[nodiscard]] const std::vector<tools::RecordedJoint>& joints() const { return joints_; }
  // The broad phase's box of every body, the static ground's included.
  void bounds(std::vector<Aabb>& out) const;

  // True when the scene has a moving body whose shape, mass and material added bodies copy.
  [[nodiscard]] bool can_add_bodies() const { return added_.has_value(); }
  // A copy of the scene's first moving body, dropped from above the scene at a random spot of
  // its starting area in a random orientation.
  void drop_body(std::mt19937& random);
  // A copy of the scene's first moving body thrown from `from` with `velocity` (unit: m, m/s).
  void shoot_body(const Vec3& from, const Vec3& velocity, std::mt19937& random);

  // The world's time-critical budgets (World::set_detection_budget), kept across resets.
  void set_detection_budget(std::uint64_t max_sphere_tests, double max_microseconds);

 private:
  void add_body(const Vec3& position, const Vec3& velocity, std::mt19937& random);

  tools::Scene scene_;
  tools::BuildWorldOptions build_;
  tools::SimulationSetup setup_;
  std::vector<tools::BodyShape> shapes_;
  std::vector<tools::RecordedJoint> joints_;
  std::vector<BodyId> bodies_;
  std::vector<std::uint32_t> body_shape_;
  struct Added {
    std::uint32_t shape = 0;
    BodyDesc desc;  // the pose and velocities are set per body added
  };
  std::optional<Added> added_;
  std::uint64_t max_sphere_tests_ = 0;
  double max_microseconds_ = 0.0;
  int frame_ = 0;
};

}  // namespace sphys::viewer
