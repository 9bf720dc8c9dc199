#pragma once

// A robot of a benchmark scene (the arm scene, robot_scene.h) as every engine builds it: which of
// the scene's bodies and joints are its links and joints, the link pairs that do not collide, and
// the motion its position control follows, with the gains of sphys's position law
// (RobotJointControl).

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sphys/robot_model.h"
#include "sphys/robot_world.h"

namespace sphys::compare {

// A joint-space motion through waypoints, a quintic from each to the next (at rest at each).
struct RobotMotion {
  std::vector<std::vector<double>> waypoints;  // one value per joint each. unit: rad or m
  std::vector<double> arrivals;  // when each waypoint is reached, rising, the first 0. unit: s

  // The joints' target positions and speeds at time t (unit: s); the last waypoint after the
  // last arrival.
  void targets(double t, std::vector<double>& positions, std::vector<double>& speeds) const;
};

// The motion's targets step after step, for the step that ends at each: what the engines drive to
// and what the tracking compares with.
class MotionSteps {
 public:
  MotionSteps(const RobotMotion& motion, double time_step)  // unit: s
      : motion_(&motion), time_step_(time_step) {}
  // On to the next step's targets.
  void next() {
    ++steps_;
    motion_->targets(static_cast<double>(steps_) * time_step_, positions_, speeds_);
  }
  [[nodiscard]] const std::vector<double>& positions() const { return positions_; }  // rad or m
  [[nodiscard]] const std::vector<double>& speeds() const { return speeds_; }        // rad/s or m/s

 private:
  const RobotMotion* motion_;
  double time_step_;
  std::int64_t steps_ = 0;  // taken so far
  std::vector<double> positions_;
  std::vector<double> speeds_;
};

struct BenchRobot {
  RobotModel model;         // its base where the scene stands it (World::add_robot's `base`)
  Transform base;           // the same pose, as add_robot takes it
  RobotMotion motion;       // followed under position control from the first step on
  RobotJointControl gains;  // position_gain and velocity_gain of every joint's position law
  // Its bodies are the scene's from this one on, in World::robot_bodies' order: the first is the
  // root, fixed where it stands (a static body).
  std::size_t first_body = 0;
  std::size_t body_count = 0;
  // Its joints are BenchScene::joints from this one on, in the model's joint order.
  std::size_t first_joint = 0;
  // Pairs of its bodies (scene indices) that do not collide though no joint joins them: the
  // model's allowed_link_pairs.
  std::vector<std::array<std::size_t, 2>> apart;
};

}  // namespace sphys::compare
