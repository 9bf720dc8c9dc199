#pragma once

// The rows joints are made of (as Box2D v3's joints and Jolt's constraint parts): blocks of one
// to three rows between two bodies, each row a direction of relative motion, solved in the soft
// step's manner: a spring-damper bias towards the rows' position while solving, none while
// relaxing, warm started from the impulse of the last substep. Each joint type
// (joint_hinge.cpp, ...) builds its blocks from its geometry at the bodies' current poses.

#include <cstdint>
#include <limits>
#include <type_traits>

#include <Eigen/Core>

#include "dynamics/joint_model.h"
#include "sphys/math.h"

namespace sphys {

// How a block of rows yields (Catto, "Soft Constraints", GDC 2011): the impulse it adds solves
// (K + Γ) P = −(J v − target rate + bias_rate C + Γ λ), where K is its inverse effective mass, C
// its position error and λ the impulse it applied so far in the substep, with the compliance
// Γ = relative K + absolute 1. All zero is rigid, a velocity row.
struct RowSoftness {
  float bias_rate = 0.0f;  // unit: 1/s
  float relative = 0.0f;   // unit: dimensionless
  float absolute = 0.0f;   // unit: 1/kg (linear rows) or 1/(kg·m²) (angular rows)
};

// A spring of `hertz` (unit: Hz) and damping ratio `zeta` on the rows' own effective mass over a
// substep of `h` (unit: s), as Box2D's b2MakeSoft: Γ = K / a2, a2 = h ω (2ζ + h ω).
[[nodiscard]] RowSoftness spring_softness(float hertz, float zeta, float h);
// A spring with a2 = `spring` and `bias_rate` whose stiffness is that of `mass` (unit: kg) rather
// than of the rows' effective mass: under a load of that mass's weight it yields g / ω², as the
// contacts do when they carry their load (soft_step_constraints.cpp).
[[nodiscard]] RowSoftness carried_softness(float spring, float bias_rate, float mass);

// One body of a joint as the substep left it, with the masses of the step's start (zero for a
// body that does not move: static, asleep, or the world).
struct JointBody {
  Vec3 linear = Vec3::Zero();           // unit: m/s
  Vec3 angular = Vec3::Zero();          // unit: rad/s
  float inverse_mass = 0.0f;            // unit: 1/kg
  Mat3 inverse_inertia = Mat3::Zero();  // world frame. unit: 1/(kg·m²)
  Transform pose;
};

// A joint's geometry at its bodies' current poses.
struct JointGeometry {
  Vec3 ra = Vec3::Zero();  // each anchor from its body's centre, world frame. unit: m
  Vec3 rb = Vec3::Zero();
  Vec3 d = Vec3::Zero();            // body b's anchor from body a's. unit: m
  Quat frame_a = Quat::Identity();  // the joint frames in the world
  Quat frame_b = Quat::Identity();
  // Frame a's axes as columns, turned once here: its rows read them several times a solve.
  Mat3 axes_a = Mat3::Identity();
  [[nodiscard]] Vec3 axis_a() const { return axes_a.col(0); }
  [[nodiscard]] Vec3 axis_b() const { return frame_b * Vec3::UnitX(); }
  // The two directions across body a's axis (its frame's y and z).
  [[nodiscard]] Eigen::Matrix<float, 3, 2> across() const { return axes_a.rightCols<2>(); }
};
[[nodiscard]] JointGeometry joint_geometry(const JointModel& joint, const JointBody& a,
                                           const JointBody& b);

// The angle of b's frame about a's x axis, in (−π, π]: the twist of their relative rotation
// (swing–twist decomposition), a hinge's angle and a ball joint's twist. unit: rad
[[nodiscard]] float twist_angle(const JointGeometry& g);

// `angle` off `target` the shorter way round, in [−π, π]. unit: rad
[[nodiscard]] float angle_error(float angle, float target);

// N rows: row i's rate is linear.col(i)·(v_b − v_a) + angular_b.col(i)·ω_b − angular_a.col(i)·ω_a,
// and an impulse P moves body b by +J P and body a by −J P.
template <int N>
struct RowBlock {
  Eigen::Matrix<float, 3, N> linear = Eigen::Matrix<float, 3, N>::Zero();
  Eigen::Matrix<float, 3, N> angular_a = Eigen::Matrix<float, 3, N>::Zero();
  Eigen::Matrix<float, 3, N> angular_b = Eigen::Matrix<float, 3, N>::Zero();
};
using Row = RowBlock<1>;
template <int N>
using RowVector = Eigen::Matrix<float, N, 1>;

// Rows along the columns of `directions` through the anchors: body a's at `arm_a` from its
// centre, body b's at `arm_b`. unit: m
template <int N>
RowBlock<N> linear_rows(const Eigen::Matrix<float, 3, N>& directions, const Vec3& arm_a,
                        const Vec3& arm_b) {
  RowBlock<N> rows;
  rows.linear = directions;
  for (int i = 0; i < N; ++i) {
    rows.angular_a.col(i) = arm_a.cross(directions.col(i));
    rows.angular_b.col(i) = arm_b.cross(directions.col(i));
  }
  return rows;
}
// Rows of relative turning about the columns of `axes`.
template <int N>
RowBlock<N> angular_rows(const Eigen::Matrix<float, 3, N>& axes) {
  RowBlock<N> rows;
  rows.angular_a = axes;
  rows.angular_b = axes;
  return rows;
}

// The rows' rates. unit: m/s or rad/s
template <int N>
RowVector<N> rates(const RowBlock<N>& rows, const JointBody& a, const JointBody& b) {
  return rows.linear.transpose() * (b.linear - a.linear) + rows.angular_b.transpose() * b.angular -
         rows.angular_a.transpose() * a.angular;
}

// The turn an impulse P on the rows gives each body per unit of P: I⁻¹ times the rows' angular
// parts, worked out once for a block's effective mass and its impulse.
template <int N>
struct RowTurns {
  Eigen::Matrix<float, 3, N> a;
  Eigen::Matrix<float, 3, N> b;
  RowTurns(const RowBlock<N>& rows, const JointBody& body_a, const JointBody& body_b)
      : a(body_a.inverse_inertia * rows.angular_a), b(body_b.inverse_inertia * rows.angular_b) {}
};

template <int N>
void apply_linear(const RowBlock<N>& rows, const RowVector<N>& impulse, JointBody& a,
                  JointBody& b) {
  const Vec3 linear = rows.linear * impulse;
  a.linear -= a.inverse_mass * linear;
  b.linear += b.inverse_mass * linear;
}

template <int N>
void apply(const RowBlock<N>& rows, const RowTurns<N>& turns, const RowVector<N>& impulse,
           JointBody& a, JointBody& b) {
  apply_linear(rows, impulse, a, b);
  a.angular -= turns.a * impulse;
  b.angular += turns.b * impulse;
}

// An impulse alone (a warm start): the rows' angular parts times it first, then I⁻¹, fewer
// products than the turns.
template <int N>
void apply(const RowBlock<N>& rows, const RowVector<N>& impulse, JointBody& a, JointBody& b) {
  apply_linear(rows, impulse, a, b);
  a.angular -= a.inverse_inertia * (rows.angular_a * impulse);
  b.angular += b.inverse_inertia * (rows.angular_b * impulse);
}

// One solve of the rows towards `target` rates with position error `error` (unit: m or rad),
// their impulse so far `impulse` updated and clamped to [lowest, highest] row by row (a limit's
// is >= 0, a motor's bounded). Nothing where the rows cannot move the bodies.
template <int N>
void solve_rows(const RowBlock<N>& rows, const std::type_identity_t<RowVector<N>>& error,
                const std::type_identity_t<RowVector<N>>& target, const RowSoftness& soft,
                JointBody& a, JointBody& b, RowVector<N>& impulse,
                float lowest = -std::numeric_limits<float>::infinity(),
                float highest = std::numeric_limits<float>::infinity()) {
  using Square = Eigen::Matrix<float, N, N>;
  const bool rigid = soft.relative == 0.0f && soft.absolute == 0.0f;
  RowVector<N> rhs = rates(rows, a, b) - target + soft.bias_rate * error;
  if constexpr (N == 1) {
    // A row that only pushes (a limit), has not pushed yet in this substep and whose bias asks
    // for no push (short of its bound and not closing on it within the substep): its impulse
    // stays 0 and the bodies as they are, as the clamp below would leave them, so its effective
    // mass is not worked out.
    if (rigid && lowest == 0.0f && impulse(0) == 0.0f && rhs(0) >= 0.0f) return;
  }
  const RowTurns<N> turns(rows, a, b);
  Square k = (a.inverse_mass + b.inverse_mass) * (rows.linear.transpose() * rows.linear);
  k.noalias() += rows.angular_a.transpose() * turns.a;
  k.noalias() += rows.angular_b.transpose() * turns.b;
  Square softened = k;
  if (!rigid) {
    const Square compliance = soft.relative * k + soft.absolute * Square::Identity();
    softened += compliance;
    rhs += compliance * impulse;
  }
  Square inverse;
  bool invertible = false;
  if constexpr (N == 1) {
    invertible = k(0, 0) > 0.0f;
    if (invertible) inverse(0, 0) = 1.0f / softened(0, 0);
  } else {
    softened.computeInverseWithCheck(inverse, invertible);
  }
  if (!invertible) return;
  const RowVector<N> before = impulse;
  impulse = (impulse - inverse * rhs).cwiseMax(lowest).cwiseMin(highest);
  apply(rows, turns, RowVector<N>(impulse - before), a, b);
}

// A scalar row's rate, impulse and solve, as the blocks'.
[[nodiscard]] inline float rate(const Row& row, const JointBody& a, const JointBody& b) {
  return rates(row, a, b)(0);
}
inline void apply(const Row& row, float impulse, JointBody& a, JointBody& b) {
  apply(row, RowVector<1>(impulse), a, b);
}
inline void solve_row(const Row& row, float error, float target, const RowSoftness& soft,
                      JointBody& a, JointBody& b, float& impulse,
                      float lowest = -std::numeric_limits<float>::infinity(),
                      float highest = std::numeric_limits<float>::infinity()) {
  RowVector<1> accumulated(impulse);
  solve_rows(row, RowVector<1>(error), RowVector<1>(target), soft, a, b, accumulated, lowest,
             highest);
  impulse = accumulated(0);
}

// What one substep's solve knows besides the joint: its length, whether it pushes positions
// back (the solve pass) or not (relax), and the joints' own stiffness.
struct JointPass {
  float h = 0.0f;          // the substep. unit: s
  float inverse_h = 0.0f;  // unit: 1/s
  bool use_bias = true;
  RowSoftness stiff;       // the joints' rows while solving, Box2D's form (relative)
  float spring = 0.0f;     // the joints' a2 (dimensionless) and bias rate (unit: 1/s), for
  float bias_rate = 0.0f;  // carried_softness()
};

// What a joint's rows share in a collision pass, set once at its start.
struct PreparedJoint {
  std::uint32_t a = 0;  // solver slots (the world's is the ground plane's, which never moves)
  std::uint32_t b = 0;
  // The mass whose weight the joint's linear rows carry: the heavier body's, or the load they
  // carried in the last step if more (as the contacts' spring). unit: kg
  float spring_mass = 0.0f;
  RowSoftness spring;  // the joint's own spring (JointDesc::spring), over the substep
};

// A limit's row, whose position error `error` (unit: m or rad) must stay >= 0: nothing while the
// joint is short of its bound by more than a substep's approach (speculative, as Box2D's), pushed
// back softly once beyond it while solving, held rigidly while relaxing.
void solve_limit(const Row& row, float error, const JointPass& pass, JointBody& a, JointBody& b,
                 float& impulse);
// The rotation that takes frame a to frame b, as a rotation vector (the rotation locks' error).
// unit: rad
[[nodiscard]] Vec3 rotation_error(const JointGeometry& g);

// A joint's spring, motor and limits along one row whose position is `position`: the spring
// pulls to its target, the motor drives the rate, and the limits stop the position at their
// bounds (reached exactly: speculatively ahead of them, softly once beyond them while solving,
// rigidly while relaxing). `spring_error` is the spring's position error. As Box2D's revolute
// and prismatic joints, in that order.
void solve_axis(const Row& row, float position, float spring_error, JointModel& joint,
                const PreparedJoint& prepared, const JointPass& pass, JointBody& a, JointBody& b);
// Their warm start: the impulses they applied in the last substep.
void warm_start_axis(const Row& row, const JointImpulses& impulses, JointBody& a, JointBody& b);
// The impulse they apply along the row in a substep. unit: N·s or N·m·s
[[nodiscard]] float axis_impulse(const JointImpulses& impulses);

}  // namespace sphys
