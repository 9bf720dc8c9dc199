#pragma once

// A world of rigid bodies with sphere-trees, stepped by the pipeline of docs/architecture.md:
// velocities, bounds and broad phase, narrow phase, contacts, response, positions.

#include <memory>
#include <span>
#include <vector>

#include "sphys/collision_detector.h"
#include "sphys/contact.h"
#include "sphys/rigid_body.h"
#include "sphys/sphere_tree.h"
#include "sphys/step_stats.h"

namespace sphys {

// How contacts change velocities.
enum class ResponseMode {
  // The paper's §4: per contact, in order, the impulse magnitude of eq. 4 along the normal when
  // the contact approaches; no friction. See docs/experiment.md.
  kPaper,
};

struct WorldSettings {
  Vec3 gravity = Vec3(0.0f, -9.81f, 0.0f);  // unit: m/s²
  ResponseMode response = ResponseMode::kPaper;
  // Paper mode: passes over the contacts at most per step; a step stops early after a pass that
  // finds no approaching contact. 1 is a single pass. See docs/experiment.md.
  std::uint32_t paper_passes = 1;
  CollisionSettings collision;
  // Material of the exact ground plane (CollisionSettings::ground_plane_height), if there is one.
  float ground_restitution = 0.3f;
  float ground_friction = 0.5f;
};

// What add_body needs. The sphere-tree and the inertia are in the body frame, whose origin is the
// centre of mass.
struct BodyDesc {
  std::shared_ptr<const SphereTree> tree;
  Transform pose;                        // unit: m
  Vec3 linear_velocity = Vec3::Zero();   // unit: m/s
  Vec3 angular_velocity = Vec3::Zero();  // world frame. unit: rad/s
  float mass = 1.0f;                     // ignored for static bodies. unit: kg
  Mat3 inertia = Mat3::Identity();       // about the centre of mass, body axes. unit: kg·m²
  float restitution = 0.3f;              // 0..1
  float friction = 0.5f;                 // >= 0
  bool is_static = false;
};

class World {
 public:
  explicit World(const WorldSettings& settings = {});

  // Throws sphys::Error naming what is wrong: no tree, a non-finite pose or velocity, a rotation
  // that is not a unit quaternion (within 1e-3), a mass that is not positive and finite, an
  // inertia that is not symmetric positive definite, restitution outside 0..1, negative friction.
  BodyId add_body(const BodyDesc& desc);
  void remove_body(BodyId body);
  [[nodiscard]] const RigidBody& body(BodyId body) const { return bodies_[body.index]; }
  // Changes a body's velocities (e.g. a shot); the pose stays. Non-finite values throw.
  void set_velocity(BodyId body, const Vec3& linear, const Vec3& angular);
  // Body slots, alive or removed; index with BodyId{i}.
  [[nodiscard]] std::uint32_t body_slots() const {
    return static_cast<std::uint32_t>(bodies_.size());
  }
  [[nodiscard]] bool alive(BodyId body) const { return alive_[body.index] != 0; }

  // Advances the world by dt (unit: s, positive and finite, else sphys::Error). Never throws
  // otherwise; when a body's state stops being finite the step reports it in
  // StepStats::non_finite_body and the world stays stopped (later steps do nothing).
  const StepStats& step(float dt);
  [[nodiscard]] const StepStats& stats() const { return stats_; }
  // The contacts the last step responded to.
  [[nodiscard]] std::span<const Contact> contacts() const { return contacts_; }
  [[nodiscard]] bool stopped() const { return stopped_; }

  [[nodiscard]] const WorldSettings& settings() const { return settings_; }
  [[nodiscard]] const CollisionDetector& detector() const { return detector_; }

 private:
  WorldSettings settings_;
  CollisionDetector detector_;
  std::vector<RigidBody> bodies_;
  std::vector<std::uint8_t> alive_;
  std::vector<Contact> contacts_;
  StepStats stats_;
  bool stopped_ = false;
};

}  // namespace sphys
