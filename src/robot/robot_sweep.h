#pragma once

// How far a robot's spheres can move while its joints move (robot_motion.cpp): a motion's states
// between two posed ones are bounded from the posed ones, without posing them.

#include <cstddef>
#include <span>
#include <vector>

#include "sphys/robot_model.h"

namespace sphys {

// Per link and joint, the most a sphere centre of the link moves per unit of the joint's value,
// whatever the other joints' values: its greatest distance from the joint's axis for a turning
// joint (m per rad), 1 for a sliding one (m per m), 0 for a joint that does not move the link.
// A centre's path along a straight motion is then no longer than the sum over the joints of
// these times the joints' changes (each joint's column of the Jacobian is no longer).
class LinkSweep {
 public:
  explicit LinkSweep(const RobotModel& model);
  // The most a sphere centre of `link` moves while each joint j changes by `changes[j]` (its
  // magnitude; rad or m) along a straight motion. unit: m
  [[nodiscard]] double along(std::size_t link, std::span<const double> changes) const;

 private:
  std::size_t joints_;
  std::vector<double> rates_;  // links × joints: m per rad or m per m
};

}  // namespace sphys
