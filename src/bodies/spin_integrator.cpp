#include "bodies/spin_integrator.h"

#include <algorithm>
#include <cstddef>

#include "sphys/rigid_body.h"

namespace sphys {
namespace {

// A batch's lanes from its bodies; lanes past the last body repeat the first, so that every lane
// holds a body whose numbers are finite where its own are.
void gather(std::span<const SpinningBody> bodies, SpinBatch& batch) {
  for (int lane = 0; lane < kDoubleLanes; ++lane) {
    const SpinningBody& body =
        bodies[static_cast<std::size_t>(lane) < bodies.size() ? static_cast<std::size_t>(lane) : 0];
    const Quat& q = body.pose->rotation;
    batch.rotation[0][lane] = q.x();
    batch.rotation[1][lane] = q.y();
    batch.rotation[2][lane] = q.z();
    batch.rotation[3][lane] = q.w();
    for (int k = 0; k < 3; ++k) batch.angular_velocity[k][lane] = (*body.angular_velocity)[k];
    for (int k = 0; k < 9; ++k) {
      batch.inertia[k][lane] = body.inertia_body->data()[k];
      batch.inverse_inertia[k][lane] = body.inverse_inertia_body->data()[k];
    }
  }
}

void scatter(const SpinBatch& batch, std::span<const SpinningBody> bodies, float dt) {
  for (std::size_t lane = 0; lane < bodies.size(); ++lane) {
    const SpinningBody& body = bodies[lane];
    if ((batch.turns_too_far >> lane) & 1u) {
      integrate_position(*body.pose, *body.linear_velocity, *body.angular_velocity,
                         *body.inertia_body, *body.inverse_inertia_body, dt);
      continue;
    }
    body.pose->translation += *body.linear_velocity * dt;
    body.pose->rotation = Quat(static_cast<float>(batch.turned_rotation[3][lane]),
                               static_cast<float>(batch.turned_rotation[0][lane]),
                               static_cast<float>(batch.turned_rotation[1][lane]),
                               static_cast<float>(batch.turned_rotation[2][lane]));
    for (int k = 0; k < 3; ++k) {
      (*body.angular_velocity)[k] = static_cast<float>(batch.turned_angular_velocity[k][lane]);
    }
  }
}

}  // namespace

void integrate_positions_keeping_spin(std::span<const SpinningBody> bodies, float dt,
                                      SpinKernel kernel) {
  SpinBatch batch;
  for (std::size_t first = 0; first < bodies.size(); first += kDoubleLanes) {
    const std::span<const SpinningBody> four =
        bodies.subspan(first, std::min<std::size_t>(kDoubleLanes, bodies.size() - first));
    gather(four, batch);
    kernel(batch, static_cast<double>(dt));
    scatter(batch, four, dt);
  }
}

}  // namespace sphys
