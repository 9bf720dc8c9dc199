#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "sphys/tools/triangle_mesh.h"

namespace sphys::tools::build {

// The cells of a uniform grid over a box, for the tools' spatial lookups: which cell a point
// falls in and each cell's place in a flat array (x fastest). Points outside the box go to the
// nearest cell, so a query near the edge still finds what lies in the border cells.
struct GridCells {
  GridCells(const Box3d& domain, double cell_size) : origin(domain.min()), cell(cell_size) {
    for (int axis = 0; axis < 3; ++axis) {
      dims[axis] = std::max(1, static_cast<int>(std::ceil(domain.sizes()[axis] / cell)));
    }
  }

  [[nodiscard]] std::array<int, 3> cell_of(const Vec3d& p) const {
    std::array<int, 3> c{};
    for (int axis = 0; axis < 3; ++axis) {
      const double t = std::floor((p[axis] - origin[axis]) / cell);
      c[axis] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(dims[axis] - 1)));
    }
    return c;
  }
  [[nodiscard]] bool contains(const std::array<int, 3>& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < dims[0] && c[1] < dims[1] &&
           c[2] < dims[2];
  }
  [[nodiscard]] std::size_t index(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * static_cast<std::size_t>(dims[1]) +
            static_cast<std::size_t>(c[1])) *
               static_cast<std::size_t>(dims[0]) +
           static_cast<std::size_t>(c[0]);
  }
  [[nodiscard]] std::size_t count() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
           static_cast<std::size_t>(dims[2]);
  }

  Vec3d origin;
  double cell;  // unit: m
  std::array<int, 3> dims{1, 1, 1};
};

}  // namespace sphys::tools::build
