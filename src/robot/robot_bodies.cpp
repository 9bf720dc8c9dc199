#include "robot/robot_bodies.h"

#include <algorithm>
#include <deque>
#include <string>

#include "sphys/error.h"

namespace sphys {
namespace {

// The most children a node of a robot link's tree has (SphereTree's largest branching).
constexpr int kLinkTreeBranching = 8;

// The sphere about the middle of the spheres' box that holds them all.
Sphere bound_spheres(std::span<const Sphere> spheres) {
  Aabb box;
  for (const Sphere& s : spheres) {
    box.extend(s.center - Vec3::Constant(s.radius));
    box.extend(s.center + Vec3::Constant(s.radius));
  }
  Sphere bound{0.5f * (box.min + box.max), 0.0f};
  for (const Sphere& s : spheres) {
    bound.radius = std::max(bound.radius, (s.center - bound.center).norm() + s.radius);
  }
  return bound;
}

// A node's spheres: a run of `leaves`, the levels under it, and where its children's runs start.
struct Run {
  std::size_t begin = 0;
  std::size_t end = 0;
  int levels_below = 0;
  std::int32_t parent = -1;
};

}  // namespace

SphereTree tree_over_spheres(std::span<const Sphere> leaves) {
  if (leaves.empty()) throw Error("a robot link's tree needs at least one sphere");
  std::vector<Sphere> spheres(leaves.begin(), leaves.end());
  int levels_below = 0;
  for (std::size_t reach = 1; reach < spheres.size(); reach *= kLinkTreeBranching) ++levels_below;
  // Breadth first: every node's children are queued together, after all of the level above.
  std::vector<SphereTreeNode> nodes;
  std::deque<Run> open = {{0, spheres.size(), levels_below, -1}};
  while (!open.empty()) {
    const Run run = open.front();
    open.pop_front();
    const auto span = std::span(spheres).subspan(run.begin, run.end - run.begin);
    const auto index = static_cast<std::int32_t>(nodes.size());
    nodes.push_back({run.levels_below == 0 ? span.front() : bound_spheres(span), run.parent});
    if (run.levels_below == 0) continue;
    // Split along the longest extent of the centres, into runs that fill the levels below.
    Aabb centres;
    for (const Sphere& s : span) centres.extend(s.center);
    int axis = 0;
    (centres.max - centres.min).maxCoeff(&axis);
    std::ranges::sort(span, {}, [axis](const Sphere& s) { return s.center[axis]; });
    std::size_t capacity = 1;
    for (int l = 1; l < run.levels_below; ++l) capacity *= kLinkTreeBranching;
    const std::size_t count = span.size();
    const std::size_t children = (count + capacity - 1) / capacity;
    for (std::size_t c = 0; c < children; ++c) {
      open.push_back({run.begin + c * count / children, run.begin + (c + 1) * count / children,
                      run.levels_below - 1, index});
    }
  }
  return SphereTree::from_nodes(nodes, kLinkTreeBranching);
}

RobotPlan plan_robot_bodies(const RobotModel& model, bool fixed_root) {
  RobotPlan plan;
  plan.bodies.resize(model.joints.size() + 1);
  plan.link_body.resize(model.links.size());
  // Each link's frame in its body's link frame, before the centre of mass is known.
  std::vector<Eigen::Isometry3d> link_in_own(model.links.size(), Eigen::Isometry3d::Identity());
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    if (l == 0 || link.joint >= 0) {
      const std::uint32_t body = l == 0 ? 0 : static_cast<std::uint32_t>(link.joint) + 1;
      plan.link_body[l] = body;
      plan.bodies[body].link = static_cast<std::int32_t>(l);
    } else {  // parents come first: the parent's body is known
      const auto parent = static_cast<std::size_t>(link.parent);
      plan.link_body[l] = plan.link_body[parent];
      link_in_own[l] = link_in_own[parent] * link.origin;
    }
  }
  // Masses and centres summed, then inertias about the common centre (parallel axes).
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    RobotBodyPlan& body = plan.bodies[plan.link_body[l]];
    body.mass += model.links[l].mass;
    body.center_of_mass += model.links[l].mass * (link_in_own[l] * model.links[l].center_of_mass);
  }
  for (RobotBodyPlan& body : plan.bodies) {
    if (body.mass > 0.0) body.center_of_mass /= body.mass;
  }
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    const RobotModel::Link& link = model.links[l];
    RobotBodyPlan& body = plan.bodies[plan.link_body[l]];
    const Eigen::Matrix3d turn = link_in_own[l].linear();
    const Eigen::Vector3d offset = link_in_own[l] * link.center_of_mass - body.center_of_mass;
    body.inertia += turn * link.inertia * turn.transpose() +
                    link.mass * (offset.squaredNorm() * Eigen::Matrix3d::Identity() -
                                 offset * offset.transpose());
  }
  plan.link_in_body.resize(model.links.size());
  for (std::size_t l = 0; l < model.links.size(); ++l) {
    plan.link_in_body[l] =
        Eigen::Translation3d(-plan.bodies[plan.link_body[l]].center_of_mass) * link_in_own[l];
  }
  std::vector<std::vector<Sphere>> spheres(plan.bodies.size());
  for (std::size_t s = 0; s < model.spheres.size(); ++s) {
    const Sphere& sphere = model.spheres[s];
    if (!(sphere.radius > 0.0f)) continue;
    const auto link = static_cast<std::size_t>(model.sphere_links[s]);
    const Eigen::Vector3d centre = plan.link_in_body[link] * sphere.center.cast<double>();
    spheres[plan.link_body[link]].push_back({centre.cast<float>(), sphere.radius});
  }
  for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
    RobotBodyPlan& body = plan.bodies[b];
    const std::string who = "robot '" + model.name + "': link '" +
                            model.links[static_cast<std::size_t>(body.link)].name + "'";
    if (spheres[b].empty()) {
      throw Error(who + " has no spheres (nor has any link fixed to it) to collide with");
    }
    if (!(body.mass > 0.0) && !(b == 0 && fixed_root)) {
      throw Error(who +
                  " has no mass (nor has any link fixed to it): no <inertial> and no "
                  "geometry to give it one");
    }
    body.tree = std::make_shared<const SphereTree>(tree_over_spheres(spheres[b]));
  }
  return plan;
}

}  // namespace sphys
