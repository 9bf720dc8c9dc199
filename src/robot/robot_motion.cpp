// Straight motions of a robot: their states along the segment in joint space, posed and checked
// coarse to fine, those of a short motion together (ConfigurationChecker::Run::gather). Without
// self-collision, a kernel call's states spread along a short motion are posed first, and the
// others bounded from them (LinkSweep) before any more is posed.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "robot/configuration_layout.h"
#include "robot/robot_kinematics.h"
#include "robot/robot_pose_scratch.h"
#include "sphys/error.h"
#include "sphys/robot_check.h"

namespace sphys {
namespace {

// The most states one motion may be cut into: more is a resolution too fine for its length.
constexpr double kMostMotionStates = 1e7;
// Motions of up to this many states are posed whole and checked together. unit: states
constexpr std::uint32_t kStatesCheckedTogether = 256;
// A state's place in the order of posing, before it has one.
constexpr std::uint32_t kNotPosed = std::numeric_limits<std::uint32_t>::max();

// Each link's box, kernel lanes' rows low x, y, z, high x, y, z (PoseScratch::boxes), grown to
// hold `boxes`' lane by lane.
void unite_lanes(const PoseLane* boxes, std::size_t links, PoseLane* united) {
  for (std::size_t row = 0; row < 6 * links; ++row) {
    const float* in = boxes[row].v;
    float* out = united[row].v;
    if (row % 6 < 3) {
      for (int i = 0; i < kPoseLanes; ++i) out[i] = std::min(out[i], in[i]);
    } else {
      for (int i = 0; i < kPoseLanes; ++i) out[i] = std::max(out[i], in[i]);
    }
  }
}

// Each link's box over the lanes of `united` into `boxes`: six floats a link, Run::bound's rows.
void fold_lanes(const PoseLane* united, std::size_t links, float* boxes) {
  for (std::size_t row = 0; row < 6 * links; ++row) {
    const float* in = united[row].v;
    float folded = in[0];
    for (int i = 1; i < kPoseLanes; ++i) {
      folded = row % 6 < 3 ? std::min(folded, in[i]) : std::max(folded, in[i]);
    }
    boxes[row] = folded;
  }
}

// The order in which a motion's `states` states are checked, into `order`: both ends, then the
// midpoints of ever finer halves, breadth first, so that a collision anywhere along it is met
// early. `spans` and `finer` are its working lists.
void coarse_to_fine(std::uint32_t states, std::vector<std::uint32_t>& order,
                    std::vector<std::array<std::uint32_t, 2>>& spans,
                    std::vector<std::array<std::uint32_t, 2>>& finer) {
  order.assign(1, 0);
  if (states > 1) order.push_back(states - 1);
  spans.assign(1, {0, states - 1});
  while (!spans.empty()) {
    finer.clear();
    for (const auto& [low, high] : spans) {
      if (high - low < 2) continue;
      const std::uint32_t middle = low + (high - low) / 2;
      order.push_back(middle);
      finer.push_back({low, middle});
      finer.push_back({middle, high});
    }
    spans.swap(finer);
  }
}

}  // namespace

MotionResult RobotChecker::check_motion(std::span<const double> from, std::span<const double> to,
                                        double resolution) const {
  const std::size_t joints = model_.joints.size();
  if (from.size() != joints || to.size() != joints) {
    throw Error("a motion needs " + std::to_string(joints) + " joint values at each end, got " +
                std::to_string(from.size()) + " and " + std::to_string(to.size()));
  }
  if (!within_limits(from.data(), 1)) check_joint_values(model_, from, "from");  // names it
  if (!within_limits(to.data(), 1)) check_joint_values(model_, to, "to");
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("resolution must be positive and finite, got " + std::to_string(resolution));
  }
  double length = 0.0;
  for (std::size_t j = 0; j < joints; ++j) length += (to[j] - from[j]) * (to[j] - from[j]);
  length = std::sqrt(length);
  const double steps = std::ceil(length / resolution);
  if (steps + 1.0 > kMostMotionStates) {
    throw Error("resolution " + std::to_string(resolution) + " cuts a motion of length " +
                std::to_string(length) + " into more than " +
                std::to_string(static_cast<long long>(kMostMotionStates)) + " states");
  }
  MotionResult result;
  result.states = static_cast<std::uint32_t>(std::max(1.0, steps)) + 1;
  const std::uint32_t last = result.states - 1;
  const auto state = [&](std::uint32_t k, double* out) {
    const double along = static_cast<double>(k) / last;
    for (std::size_t j = 0; j < joints; ++j) {
      // The ends exactly, and every state between them within both ends' limits.
      out[j] = k == last ? to[j]
                         : std::clamp(from[j] + (to[j] - from[j]) * along, model_.joints[j].lower,
                                      model_.joints[j].upper);
    }
  };
  const std::size_t per = model_.spheres.size() * kFloatsPerSphere;
  std::unique_ptr<Workspace> workspace = take_workspace();
  PoseScratch& scratch = workspace->pose;
  ConfigurationChecker::Run& checks = workspace->checks;
  std::vector<std::uint32_t>& order = workspace->order;
  if (workspace->order_states != result.states) {  // the last motion's order is kept
    coarse_to_fine(result.states, order, workspace->spans, workspace->finer);
    workspace->order_states = result.states;
  }
  std::vector<double>& values = workspace->values;
  values.resize(kPoseLanes * joints);
  // A motion of few states is posed whole and its states checked together (each link's groups
  // collected once, for the bound of all its states); a longer one a block of states at a time.
  const bool together = result.states <= kStatesCheckedTogether;
  // Self-collision reads every sphere: every state posed whole. Else the links' poses alone,
  // each link bounded over the states from its poses and only the spheres of links near a body
  // placed.
  const bool whole = checker_.reads_every_sphere();
  std::vector<float>& posed = workspace->posed;
  if (together && whole) {
    posed.resize(result.states * per);
    for (std::uint32_t first = 0; first < result.states; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, result.states - first);
      for (std::size_t i = 0; i < n; ++i) {
        state(first + static_cast<std::uint32_t>(i), values.data() + i * joints);
      }
      std::copy_n(pose(values.data(), n, scratch), n * per, posed.data() + first * per);
    }
    checks.gather(posed.data(), result.states);
  } else if (together) {
    const std::size_t links = checker_.links();
    const std::size_t block_floats = scratch.links.size() * kPoseLanes;
    const std::size_t blocks = (result.states + kPoseLanes - 1) / kPoseLanes;
    // The order the states are posed in: first a kernel call's worth spread evenly along the
    // motion, both ends among them, then the others in order.
    std::vector<std::uint32_t>& posed_states = workspace->posed_states;
    std::vector<std::uint32_t>& state_slots = workspace->state_slots;
    const std::uint32_t spread = std::min<std::uint32_t>(result.states, kPoseLanes);
    posed_states.clear();
    state_slots.assign(result.states, kNotPosed);
    std::uint32_t widest_gap = 0;  // between neighbouring spread states. unit: states
    for (std::uint32_t i = 0; i < spread; ++i) {
      const auto k =
          static_cast<std::uint32_t>((std::uint64_t{i} * last + (spread - 1) / 2) / (spread - 1));
      if (i > 0) widest_gap = std::max(widest_gap, k - posed_states.back());
      state_slots[k] = i;
      posed_states.push_back(k);
    }
    for (std::uint32_t k = 0; k < result.states; ++k) {
      if (state_slots[k] != kNotPosed) continue;
      state_slots[k] = static_cast<std::uint32_t>(posed_states.size());
      posed_states.push_back(k);
    }
    // Poses the states of block b (kernel lanes) into `scratch`: the links' poses and boxes.
    const auto pose_block = [&](std::size_t b) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, result.states - b * kPoseLanes);
      for (std::size_t i = 0; i < n; ++i) {
        state(posed_states[b * kPoseLanes + i], values.data() + i * joints);
      }
      (void)pose(values.data(), n, scratch, false);
    };
    const auto any_near = [&] {
      for (std::size_t l = 0; l < links; ++l) {
        if (checks.near(l)) return true;
      }
      return false;
    };
    // Each link's box over the spread states, a kernel call's lanes, exactly as posed.
    std::vector<PoseLane>& united = workspace->united;
    pose_block(0);
    united.assign(scratch.boxes.begin(), scratch.boxes.begin() + 6 * links);
    std::vector<float>& boxes = workspace->boxes;
    boxes.resize(6 * links);
    fold_lanes(united.data(), links, boxes.data());
    if (spread < result.states) {
      // Every state lies within half the widest gap of a spread one: each link's box over the
      // spread states, widened by how far its spheres can move in that part of the motion,
      // holds them all. Everything far from that, the motion is free without posing the rest.
      std::vector<double>& changes = workspace->changes;
      changes.resize(joints);
      const double part = static_cast<double>(widest_gap / 2) / last;
      for (std::size_t j = 0; j < joints; ++j) changes[j] = std::abs(to[j] - from[j]) * part;
      std::vector<float>& widened = workspace->widened;
      widened = boxes;
      for (std::size_t l = 0; l < links; ++l) {
        const float reach = static_cast<float>(compiled_->sweep.along(l, changes) * (1.0 + 1e-6)) +
                            compiled_->sweep_margin;
        for (std::size_t r = 0; r < 3; ++r) {
          widened[6 * l + r] -= reach;
          widened[6 * l + 3 + r] += reach;
        }
      }
      checks.bound(widened.data(), 1);
      if (!any_near()) {
        keep_workspace(std::move(workspace));
        return result;
      }
    }
    // Then every state posed: each link's box over them all, and only the spheres of links near a
    // body placed, state by state from the poses kept.
    std::vector<float>& link_poses = workspace->link_poses;  // every block's, as posed
    link_poses.resize(blocks * block_floats);
    std::copy_n(scratch.links.front().v, block_floats, link_poses.data());
    for (std::size_t b = 1; b < blocks; ++b) {
      pose_block(b);
      std::copy_n(scratch.links.front().v, block_floats, link_poses.data() + b * block_floats);
      unite_lanes(scratch.boxes.data(), links, united.data());
    }
    fold_lanes(united.data(), links, boxes.data());
    checks.bound(boxes.data(), 1);
    if (!any_near()) {  // every link far from every body in every state
      keep_workspace(std::move(workspace));
      return result;
    }
    std::vector<std::uint32_t>& near_spheres = workspace->near_spheres;
    near_spheres.clear();
    for (std::size_t l = 0; l < links; ++l) {
      if (!checks.near(l)) continue;
      near_spheres.insert(near_spheres.end(),
                          compiled_->link_spheres.begin() + compiled_->link_first[l],
                          compiled_->link_spheres.begin() + compiled_->link_first[l + 1]);
    }
    posed.resize(result.states * per);
    for (std::size_t b = 0; b < blocks; ++b) {
      // Lanes past the motion's last state pose the block's first again: the same bits, written
      // to the same place.
      const std::size_t n = std::min<std::size_t>(kPoseLanes, result.states - b * kPoseLanes);
      std::array<float*, kPoseLanes> out;
      for (std::size_t i = 0; i < kPoseLanes; ++i) {
        out[i] = posed.data() + posed_states[b * kPoseLanes + (i < n ? i : 0)] * per;
      }
      compiled_->kernel.place(compiled_->tables, link_poses.data() + b * block_floats,
                              near_spheres.data(), near_spheres.size(), out.data());
    }
    checks.gather_bounded(posed.data(), result.states);
  }
  // Checks `count` states, in order: the position of the first that collides (its answer in
  // result.collision), else -1.
  const auto check_states = [&](const std::uint32_t* states, std::size_t count) {
    for (std::size_t first = 0; first < count; first += kPoseLanes) {
      const std::size_t n = std::min<std::size_t>(kPoseLanes, count - first);
      const float* block = nullptr;
      if (!together) {
        for (std::size_t i = 0; i < n; ++i) state(states[first + i], values.data() + i * joints);
        block = pose(values.data(), n, scratch, whole);
      }
      for (std::size_t i = 0; i < n; ++i) {
        const ConfigurationResult answer =
            together ? checks.check_gathered(states[first + i])
                     : (whole ? checks.check(block + i * per) : check_from_links(i, *workspace));
        if (!answer.free) {
          result.collision = answer;
          return static_cast<std::int64_t>(first + i);
        }
      }
    }
    return std::int64_t{-1};
  };
  const std::int64_t hit = check_states(order.data(), order.size());
  if (hit >= 0) {
    // The states before the one found, those not checked yet, in order: the first that collides.
    const std::uint32_t found = order[static_cast<std::size_t>(hit)];
    std::vector<std::uint8_t>& checked = workspace->checked;
    checked.assign(found, 0);
    for (std::int64_t i = 0; i < hit; ++i) {
      const std::uint32_t k = order[static_cast<std::size_t>(i)];
      if (k < found) checked[k] = 1;
    }
    std::vector<std::uint32_t>& before = workspace->before;
    before.clear();
    for (std::uint32_t k = 0; k < found; ++k) {
      if (checked[k] == 0) before.push_back(k);
    }
    const ConfigurationResult at_found = result.collision;
    const std::int64_t earlier = check_states(before.data(), before.size());
    const std::uint32_t first = earlier < 0 ? found : before[static_cast<std::size_t>(earlier)];
    if (earlier < 0) result.collision = at_found;
    result.free = false;
    result.first_collision = static_cast<std::int32_t>(first);
    result.last_free = first == 0 ? 0.0 : static_cast<double>(first - 1) / last;
  }
  keep_workspace(std::move(workspace));
  return result;
}

void RobotChecker::check_motions(std::span<const double> from, std::span<const double> to,
                                 double resolution, std::span<MotionResult> results,
                                 const Parallel* parallel) const {
  const std::size_t joints = model_.joints.size();
  if (from.size() != to.size() || from.size() != results.size() * joints) {
    throw Error("motions: " + std::to_string(from.size()) + " and " + std::to_string(to.size()) +
                " values for " + std::to_string(results.size()) + " motions of " +
                std::to_string(joints) + " joints");
  }
  const auto one = [&](std::size_t m) {
    results[m] =
        check_motion(from.subspan(m * joints, joints), to.subspan(m * joints, joints), resolution);
  };
  for_each_on(parallel, results.size(), one);
}

}  // namespace sphys
