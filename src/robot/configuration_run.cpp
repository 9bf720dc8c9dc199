// ConfigurationChecker::Run: configurations checked one at a time on one thread, its working
// memory kept from one to the next; several gathered and bounded together (a motion's states), or
// bounded by the caller from its links' poses (RobotChecker).

#include <algorithm>
#include <limits>
#include <memory>
#include <string>

#include "robot/configuration_layout.h"
#include "robot/configuration_scratch.h"
#include "sphys/error.h"

namespace sphys {

ConfigurationChecker::Run::Run(const ConfigurationChecker& checker)
    : checker_(&checker),
      scratch_(std::make_unique<Scratch>(checker.links_, checker.link_count_)) {}

ConfigurationChecker::Run::~Run() = default;

ConfigurationResult ConfigurationChecker::Run::check(const float* spheres) {
  gathered_count_ = 0;  // the scratch is this configuration's now
  return checker_->check_one(spheres, *scratch_);
}

void ConfigurationChecker::Run::gather(const float* spheres, std::size_t configurations) {
  gathered_finite_ = scratch_->bound_spheres(spheres, configurations, checker_->links_, false);
  scratch_->box_links_from_spheres(checker_->links_);
  checker_->collect_candidates(*scratch_);
  scratch_->near_known = false;
  gathered_ = spheres;
  gathered_count_ = configurations;
  gathered_bounded_ = false;
}

void ConfigurationChecker::Run::gather_bounded(const float* spheres, std::size_t configurations) {
  if (checker_->reads_every_sphere()) {
    throw Error("gather_bounded: self-collision reads every sphere; gather them all instead");
  }
  gathered_finite_ = scratch_->bound_spheres(spheres, configurations, checker_->links_, true);
  scratch_->near_known = false;
  gathered_ = spheres;
  gathered_count_ = configurations;
  gathered_bounded_ = true;
}

ConfigurationResult ConfigurationChecker::Run::check_gathered(std::size_t configuration) {
  Scratch& scratch = *scratch_;
  const ConfigurationChecker& checker = *checker_;
  if (configuration >= gathered_count_) {
    throw Error("check_gathered: configuration " + std::to_string(configuration) + " of " +
                std::to_string(gathered_count_) + " gathered");
  }
  const std::size_t per = checker.links_.size() * kFloatsPerSphere;
  const float* spheres = gathered_ + configuration * per;
  // A non-finite sphere anywhere: each configuration on its own (which names the sphere), the
  // scratch bounding that configuration alone each time, or, bounded, within the links' boxes
  // given.
  if (!gathered_finite_) {
    return gathered_bounded_ ? checker.answer(spheres, scratch, false)
                             : checker.check_one(spheres, scratch);
  }
  if (!scratch.near_known) {
    scratch.near.clear();
    // A sphere whose box over all the gathered configurations, as a sphere, touches nothing
    // cannot touch anything in any of them.
    for (std::size_t i = 0; i < checker.links_.size(); ++i) {
      const auto link = static_cast<std::size_t>(checker.links_[i]);
      if (scratch.candidate_count[link] == 0) continue;
      // With the bounds' relative margin against the rounding of the half diagonal.
      const float* lo = &scratch.least[i * kFloatsPerSphere];
      const float* hi = &scratch.greatest[i * kFloatsPerSphere];
      const Vec3 middle = 0.5f * (Vec3(lo[0], lo[1], lo[2]) + Vec3(hi[0], hi[1], hi[2]));
      const float reach =
          (0.5f * (Vec3(hi[0], hi[1], hi[2]) - Vec3(lo[0], lo[1], lo[2])).norm() + hi[3]) *
          (1.0f + 1e-5f);
      const float bound[4] = {middle.x(), middle.y(), middle.z(), reach};
      if (checker.sphere_touches(bound, link, scratch) >= 0) {
        scratch.near.push_back(static_cast<std::uint32_t>(i));
      }
    }
    scratch.near_known = true;
  }
  ConfigurationResult result;
  for (const std::uint32_t i : scratch.near) {
    const std::int32_t body = checker.sphere_touches(
        spheres + i * kFloatsPerSphere, static_cast<std::size_t>(checker.links_[i]), scratch);
    if (body >= 0) return {false, static_cast<std::int32_t>(i), body, -1};
  }
  std::int32_t other = -1;
  const std::int32_t sphere = checker.self_collision(spheres, other);
  if (sphere >= 0) return {false, sphere, -1, other};
  return result;
}

void ConfigurationChecker::Run::bound(const float* boxes, std::size_t stride) {
  gathered_count_ = 0;  // the scratch is this configuration's now
  Scratch& scratch = *scratch_;
  // The box around the links that have spheres (no other is walked). A NaN is left out of it
  // (std::min and max keep the first operand against it), as it leaves its link meeting nothing.
  Vec3 low = Vec3::Constant(std::numeric_limits<float>::infinity());
  Vec3 high = -low;
  for (std::size_t l = 0; l < checker_->link_count_; ++l) {
    for (std::size_t a = 0; a < 3; ++a) {
      const float link_low = boxes[(6 * l + a) * stride];
      const float link_high = boxes[(6 * l + 3 + a) * stride];
      scratch.row(a)[l] = link_low;
      scratch.row(3 + a)[l] = link_high;
      if (scratch.spheres[l] == 0) continue;
      low[a] = std::min(low[a], link_low);
      high[a] = std::max(high[a], link_high);
    }
  }
  scratch.around = {low, high};
  scratch.around_known = true;
  checker_->collect_candidates(scratch);
}

bool ConfigurationChecker::Run::near(std::size_t link) const {
  return scratch_->candidate_count[link] != 0;
}

ConfigurationResult ConfigurationChecker::Run::check_bounded(const float* spheres) {
  return checker_->answer(spheres, *scratch_, checker_->reads_every_sphere());
}

}  // namespace sphys
