#include "robot/robot_sweep.h"

#include <algorithm>
#include <cmath>

namespace sphys {

LinkSweep::LinkSweep(const RobotModel& model)
    : joints_(model.joints.size()), rates_(model.links.size() * model.joints.size(), 0.0) {
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    // The farthest centre of the link from its frame's origin; then, up the chain, from each
    // ancestor's frame origin, which a turning joint's axis passes through.
    double far = 0.0;  // unit: m
    for (std::size_t s = 0; s < model.spheres.size(); ++s) {
      if (static_cast<std::size_t>(model.sphere_links[s]) == l) {
        far = std::max(far, static_cast<double>(model.spheres[s].center.norm()));
      }
    }
    for (auto m = static_cast<std::int32_t>(l); m >= 0;) {
      const RobotModel::Link& link = model.links[static_cast<std::size_t>(m)];
      if (link.joint >= 0) {
        const RobotModel::Joint& joint = model.joints[static_cast<std::size_t>(link.joint)];
        double& rate = rates_[l * joints_ + static_cast<std::size_t>(link.joint)];
        if (joint.type == RobotJointType::kPrismatic) {
          rate = 1.0;
          // The slide moves the link's frame away from its parent's by up to its longest travel.
          far += std::max(std::abs(joint.lower), std::abs(joint.upper));
        } else {
          rate = far;
        }
      }
      far += link.origin.translation().norm();
      m = link.parent;
    }
  }
}

double LinkSweep::along(std::size_t link, std::span<const double> changes) const {
  double moved = 0.0;
  const double* rates = rates_.data() + link * joints_;
  for (std::size_t j = 0; j < joints_; ++j) moved += rates[j] * changes[j];
  return moved;
}

}  // namespace sphys
