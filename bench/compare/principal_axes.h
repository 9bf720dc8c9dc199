#pragma once

// The principal axes of an inertia tensor, for engines that take a diagonal inertia (Bullet):
// their body frame is the principal frame, turned by `rotation` from the mesh's axes.

#include <Eigen/Eigenvalues>

#include "sphys/math.h"

namespace sphys::compare {

struct PrincipalAxes {
  // Maps principal-frame vectors to body-frame (mesh-axes) vectors: I = R diag(moments) Rᵀ.
  Quat rotation = Quat::Identity();
  Vec3 moments = Vec3::Ones();  // unit: kg·m²
};

inline PrincipalAxes principal_axes(const Mat3& inertia) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia);
  Mat3 axes = eigen.eigenvectors();
  if (axes.determinant() < 0.0f) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  return {Quat(axes).normalized(), eigen.eigenvalues()};
}

}  // namespace sphys::compare
