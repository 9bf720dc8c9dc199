#pragma once

// One physics engine running the benchmark scene, behind the interface the comparison times.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "sphys/collision_settings.h"

namespace sphys::compare {

struct BodyState {
  Transform pose;  // of the body frame of BenchScene (centre of mass, mesh axes)
  Vec3 linear_velocity = Vec3::Zero();   // unit: m/s
  Vec3 angular_velocity = Vec3::Zero();  // world frame. unit: rad/s
};

class Engine {
 public:
  virtual ~Engine() = default;
  // One step of BenchScene::time_step: the call the comparison times.
  virtual void step() = 0;
  // The bodies now, in the scene's order.
  virtual void read(std::vector<BodyState>& out) const = 0;
  // The last step's contacts as the engine counts them, and the deepest penetration among them
  // (the engine's own measure: its contact depths). unit: m
  [[nodiscard]] virtual std::uint32_t contacts() const = 0;
  [[nodiscard]] virtual float deepest_penetration() const = 0;
  // How many of the bodies the engine itself has put to sleep now (asleep, deactivated,
  // disabled); nullopt for an engine without sleeping.
  [[nodiscard]] virtual std::optional<std::uint32_t> asleep() const { return std::nullopt; }
  // The scene's robot's joint positions now, in its model's joint order; empty without a robot.
  // unit: rad or m
  [[nodiscard]] virtual std::vector<double> robot_positions() const { return {}; }
  // How many joints the engine holds between the bodies (its free joints aside).
  [[nodiscard]] virtual std::uint32_t joints() const = 0;
  // What went wrong so far that makes the run suspect (e.g. contacts dropped); empty if nothing.
  [[nodiscard]] virtual std::string warnings() const { return {}; }
};

// The engines by name: "sphys", "sphys-paper", "sphys-sap" (plausible mode with one Sweep &
// Prune instead of the cells), "bullet-spheres", "bullet-hull", "ode", "mujoco"; "sphys:T",
// "sphys-paper:T" and "sphys-sap:T" step sphys on T threads (0: all). Throws sphys::Error for an
// unknown name, and for an engine that cannot build the scene's robot (only sphys's plausible mode
// and MuJoCo can).
[[nodiscard]] std::unique_ptr<Engine> make_engine(const std::string& name, const BenchScene& scene);
[[nodiscard]] std::vector<std::string> engine_names();

// Each engine's maker, in its own file.
// `broad_phase` unset: the mode's.
[[nodiscard]] std::unique_ptr<Engine> make_sphys_engine(
    const BenchScene& scene, bool paper, std::uint32_t threads,
    std::optional<BroadPhaseKind> broad_phase = std::nullopt);
[[nodiscard]] std::unique_ptr<Engine> make_bullet_engine(const BenchScene& scene, bool hull);
[[nodiscard]] std::unique_ptr<Engine> make_ode_engine(const BenchScene& scene);
[[nodiscard]] std::unique_ptr<Engine> make_mujoco_engine(const BenchScene& scene);

}  // namespace sphys::compare
