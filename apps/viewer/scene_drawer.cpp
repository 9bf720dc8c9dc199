#include "scene_drawer.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sphys/tools/primitives.h"
#include "sphys/tools/scene_meshes.h"

namespace sphys::viewer {
namespace {

const Eigen::Vector3f kBodyColour(0.86f, 0.72f, 0.52f);
const Eigen::Vector3f kAsleepColour(0.55f, 0.62f, 0.80f);
const Eigen::Vector3f kGroundColour(0.50f, 0.53f, 0.50f);
const Eigen::Vector3f kSphereColour(0.25f, 0.55f, 0.95f);
// The spheres are see-through enough that the body shows under a layer or two of them.
constexpr float kSphereAlpha = 0.25f;
const Eigen::Vector3f kContactColour(0.95f, 0.10f, 0.10f);
const Eigen::Vector3f kNormalColour(1.00f, 0.85f, 0.10f);
const Eigen::Vector3f kBoxColour(0.10f, 0.75f, 0.25f);
const Eigen::Vector3f kJointColour(0.90f, 0.15f, 0.90f);
// A hinge, ball or weld whose anchors are further apart than kLargeJointGap.
const Eigen::Vector3f kJointGapColour(1.00f, 0.50f, 0.00f);
// The sun's shadows cover a sphere around what the camera looks at, as wide as the view is far,
// within these bounds: wider would blur them, narrower cut them off. unit: m
constexpr float kMinShadowReach = 10.0f;
constexpr float kMaxShadowReach = 80.0f;
// Half the arms of a contact's cross, and the length of its normal. unit: m
constexpr float kContactMark = 0.03f;
constexpr float kNormalLength = 0.25f;
// Half the arms of the cross at a joint's anchor on body b. unit: m
constexpr float kJointMark = 0.05f;
// A gap between a hinge's, ball's or weld's anchors this large is drawn in kJointGapColour: the
// joint tests hold theirs under 2 mm, the ragdoll's under 2 cm (docs/joints.md). unit: m
constexpr float kLargeJointGap = 0.01f;

// The joint types whose two anchors are one point: for them the anchors' distance is the joint's
// gap (a slider's anchors slide apart, a distance joint's are its rod's ends).
bool holds_anchors_together(JointType type) {
  return type == JointType::kHinge || type == JointType::kBall || type == JointType::kWeld;
}

Eigen::Matrix4f model_matrix(const Transform& pose, float scale = 1.0f) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<3, 3>(0, 0) = pose.rotation.toRotationMatrix() * scale;
  m.block<3, 1>(0, 3) = pose.translation;
  return m;
}

}  // namespace

SceneDrawer::SceneDrawer(Renderer& renderer, const tools::Scene& scene,
                         const std::vector<tools::BodyShape>& shapes)
    : scene_(&scene), shapes_(&shapes) {
  for (const tools::BodyShape& shape : shapes) {
    shape_meshes_.push_back(renderer.add_mesh(*shape.body_mesh));
  }
  const tools::TriangleMesh ground = tools::ground_mesh(scene.ground, kPlaneSize);
  if (!ground.triangles.empty()) ground_ = renderer.add_mesh(ground);
  sphere_ = renderer.add_mesh(tools::make_icosphere(1.0, 2));
}

void SceneDrawer::draw(Renderer& renderer, LineRenderer& lines, const OrbitCamera& camera,
                       float aspect, const FrameContents& frame, const Overlays& overlays) {
  const Eigen::Matrix4f view_projection = camera.projection(aspect) * camera.view();
  if (overlays.shadows) {
    renderer.begin_shadows(camera.target,
                           std::clamp(camera.distance, kMinShadowReach, kMaxShadowReach));
    for (const BodyView& body : frame.bodies) {
      renderer.cast_shadow(shape_meshes_[body.shape], model_matrix(body.pose));
    }
    renderer.end_shadows();
  }
  renderer.begin(camera.view(), camera.projection(aspect), camera.eye());
  if (ground_) renderer.draw(*ground_, Eigen::Matrix4f::Identity(), kGroundColour);
  for (const BodyView& body : frame.bodies) {
    const bool tinted = overlays.sleeping_tint && body.asleep;
    renderer.draw(shape_meshes_[body.shape], model_matrix(body.pose),
                  tinted ? kAsleepColour : kBodyColour);
  }
  lines.begin(view_projection);
  if (overlays.boxes) draw_boxes(lines, frame.boxes);
  // See-through spheres last, so that they do not hide what lies behind them.
  if (overlays.sphere_level > 0) draw_spheres(renderer, frame.bodies, overlays.sphere_level);
  if (overlays.contacts) draw_contacts(lines, frame.contacts);
  if (overlays.joints) draw_joints(lines, frame.bodies, frame.joints);
}

// The spheres of one level of each body's tree, see-through, as in the paper's Figure 1.
void SceneDrawer::draw_spheres(Renderer& renderer, std::span<const BodyView> bodies,
                               int level) const {
  for (const BodyView& body : bodies) {
    const SphereTree& tree = *(*shapes_)[body.shape].tree;
    for (const Sphere& sphere : tree.level_spheres(std::min(level, tree.depth()) - 1)) {
      const Transform placed{body.pose.rotation, body.pose.apply(sphere.center)};
      renderer.draw(sphere_, model_matrix(placed, sphere.radius), kSphereColour, kSphereAlpha);
    }
  }
}

// A small cross at each contact point and its normal (from body a towards body b), drawn over
// everything: contacts lie between bodies, where surfaces would hide them.
void SceneDrawer::draw_contacts(LineRenderer& lines, std::span<const Contact> contacts) {
  points_.clear();
  for (const Contact& contact : contacts) {
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 arm = kContactMark * Vec3::Unit(axis);
      points_.push_back(contact.point - arm);
      points_.push_back(contact.point + arm);
    }
  }
  lines.draw(points_, kContactColour, true);
  points_.clear();
  for (const Contact& contact : contacts) {
    points_.push_back(contact.point);
    points_.push_back(contact.point + kNormalLength * contact.normal);
  }
  lines.draw(points_, kNormalColour, true);
}

void SceneDrawer::draw_boxes(LineRenderer& lines, std::span<const Aabb> boxes) {
  points_.clear();
  for (const Aabb& box : boxes) {
    if (box.empty() || !box.min.allFinite() || !box.max.allFinite()) continue;
    const auto corner = [&](int i) {
      return Vec3((i & 1) != 0 ? box.max.x() : box.min.x(),
                  (i & 2) != 0 ? box.max.y() : box.min.y(),
                  (i & 4) != 0 ? box.max.z() : box.min.z());
    };
    // The 12 edges join corners that differ in one coordinate bit.
    for (int i = 0; i < 8; ++i) {
      for (const int bit : {1, 2, 4}) {
        if ((i & bit) != 0) continue;
        points_.push_back(corner(i));
        points_.push_back(corner(i | bit));
      }
    }
  }
  lines.draw(points_, kBoxColour, false);
}

// Each joint as its bodies' arms, centre to anchor, the segment between its two anchors and a
// cross at body b's anchor, drawn over everything: a joint lies inside its bodies. A joint to
// the world has no arm on the world's side. A joint whose anchors have come apart is drawn whole
// in the gap's colour.
void SceneDrawer::draw_joints(LineRenderer& lines, std::span<const BodyView> bodies,
                              std::span<const tools::RecordedJoint> joints) {
  points_.clear();
  gap_points_.clear();
  const auto within = [&](const std::optional<std::uint32_t>& body) {
    return !body || *body < bodies.size();
  };
  const auto placed = [&](const std::optional<std::uint32_t>& body, const Vec3& anchor) {
    return body ? bodies[*body].pose.apply(anchor) : anchor;
  };
  for (const tools::RecordedJoint& joint : joints) {
    if (!within(joint.body_a) || !within(joint.body_b)) continue;
    const Vec3 a = placed(joint.body_a, joint.anchor_a);
    const Vec3 b = placed(joint.body_b, joint.anchor_b);
    const bool gapped = holds_anchors_together(joint.type) && (b - a).norm() > kLargeJointGap;
    std::vector<Eigen::Vector3f>& out = gapped ? gap_points_ : points_;
    for (const auto& [body, anchor] : {std::pair{joint.body_a, a}, {joint.body_b, b}}) {
      if (!body) continue;
      out.push_back(bodies[*body].pose.translation);
      out.push_back(anchor);
    }
    out.push_back(a);
    out.push_back(b);
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 arm = kJointMark * Vec3::Unit(axis);
      out.push_back(b - arm);
      out.push_back(b + arm);
    }
  }
  lines.draw(points_, kJointColour, true);
  lines.draw(gap_points_, kJointGapColour, true);
}

// Tall stacks rise out of view: the live view is for the pile they make. Robots are looked at
// from their root links up.
OrbitCamera frame_scene(const tools::Scene& scene) {
  OrbitCamera camera;
  if (scene.bodies.empty() && scene.robots.empty()) return camera;
  Eigen::AlignedBox3f box;
  for (const tools::BodySpec& body : scene.bodies) box.extend(body.position);
  // A robot stands on its root link's z axis (URDF's up): its root and a metre up that axis.
  for (const tools::SceneRobot& robot : scene.robots) {
    box.extend(robot.position);
    box.extend(robot.position + robot.orientation * Vec3::UnitZ());
  }
  camera.target = box.center();
  camera.target.y() = std::min(box.center().y(), static_cast<float>(scene.ground.height) + 3.0f);
  float spread = std::max(box.sizes().x(), box.sizes().z());
  if (scene.ground.kind == tools::GroundSpec::Kind::kOctreeBox) {
    spread = std::max(spread, static_cast<float>(scene.ground.size));
  }
  // Bunny piles are seen from 12 m at least; a robot arm, a metre tall, from 2 m.
  const float nearest = scene.robots.empty() ? 12.0f : 2.0f;
  camera.distance = std::clamp(1.3f * spread, nearest, 150.0f);
  return camera;
}

}  // namespace sphys::viewer
