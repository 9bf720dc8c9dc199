#pragma once

// The kinematics kernel over a lane type (core/simd.h), included by each file that instantiates
// it for its own lanes, inside that file's anonymous namespace, after core/simd.h and
// robot/robot_kinematics.h. Only correctly rounded adds and multiplies, in the same order for
// every lane type, so every width gives the same bits.

// sin q and 1 - cos q for q in [-pi, pi], from the half angle h = q / 2 in [-pi/2, pi/2]:
// sin q = 2 sin h cos h and 1 - cos q = 2 sin² h (no cancellation near q = 0). Taylor series to
// h^13 and h^14, whose truncation (below 1e-9) is far under a float's rounding.
template <class L>
void sin_and_versine(L q, L& sine, L& versine) {
  const L h = q * L::splat(0.5f);
  const L h2 = h * h;
  L s = L::splat(1.0f / 6227020800.0f);  // 1/13!, then the series' lower terms
  s = s * h2 - L::splat(1.0f / 39916800.0f);
  s = s * h2 + L::splat(1.0f / 362880.0f);
  s = s * h2 - L::splat(1.0f / 5040.0f);
  s = s * h2 + L::splat(1.0f / 120.0f);
  s = s * h2 - L::splat(1.0f / 6.0f);
  s = (s * h2 + L::splat(1.0f)) * h;
  L c = L::splat(-1.0f / 87178291200.0f);  // -1/14!
  c = c * h2 + L::splat(1.0f / 479001600.0f);
  c = c * h2 - L::splat(1.0f / 3628800.0f);
  c = c * h2 + L::splat(1.0f / 40320.0f);
  c = c * h2 - L::splat(1.0f / 720.0f);
  c = c * h2 + L::splat(1.0f / 24.0f);
  c = c * h2 - L::splat(0.5f);
  c = c * h2 + L::splat(1.0f);
  const L two = L::splat(2.0f);
  sine = two * s * c;
  versine = two * s * s;
}

// Sphere s's centre in every lane into `xyz` (rows x, y, z) and radius, at `out[lane] + 4 s`:
// its link's rotation times the centre in the link, plus the translation, added in that order.
template <class L>
void place_sphere(const sphys::KinematicsTables& k, const float* links, int s, float* const* out) {
  constexpr int W = sphys::kPoseLanes;
  const float* pose = links + static_cast<std::ptrdiff_t>(12 * W) * k.sphere_link[s];
  const float* local = k.sphere + 4 * s;
  const L x = L::splat(local[0]);
  const L y = L::splat(local[1]);
  const L z = L::splat(local[2]);
  alignas(32) float xyz[3][W];
  for (int r = 0; r < 3; ++r) {
    const L v = L::load(pose + W * (3 * r)) * x + L::load(pose + W * (3 * r + 1)) * y +
                L::load(pose + W * (3 * r + 2)) * z + L::load(pose + W * (9 + r));
    v.store(xyz[r]);
  }
  for (int i = 0; i < W; ++i) {
    float* sphere = out[i] + 4 * s;
    sphere[0] = xyz[0][i];
    sphere[1] = xyz[1][i];
    sphere[2] = xyz[2][i];
    sphere[3] = local[3];
  }
}

template <class L>
void place_block_of(const sphys::KinematicsTables& k, const float* links,
                    const std::uint32_t* spheres, std::size_t count, float* const* out) {
  for (std::size_t n = 0; n < count; ++n)
    place_sphere<L>(k, links, static_cast<int>(spheres[n]), out);
}

template <class L>
void pose_block_of(const sphys::KinematicsTables& k, const float* values, float* links,
                   float* boxes, float* out) {
  constexpr int W = sphys::kPoseLanes;
  static_assert(L::kWidth == W);
  const auto lane = [&](const float* p) { return L::load(p); };
  for (int l = 0; l < k.links; ++l) {
    // The link's motion M in its parent's frame: rotation m[0..8], translation m[9..11].
    L m[12];
    const float* a = k.a + 9 * l;
    const float* t = k.t + 3 * l;
    for (int i = 0; i < 9; ++i) m[i] = L::splat(a[i]);
    for (int i = 0; i < 3; ++i) m[9 + i] = L::splat(t[i]);
    if (k.motion[l] == sphys::LinkMotion::kTurn) {
      L sine, versine;
      sin_and_versine(lane(values + W * k.joint[l]), sine, versine);
      const float* b = k.b + 9 * l;
      const float* c = k.c + 9 * l;
      for (int i = 0; i < 9; ++i) {
        m[i] = m[i] + sine * L::splat(b[i]) + versine * L::splat(c[i]);
      }
    } else if (k.motion[l] == sphys::LinkMotion::kSlide) {
      const L q = lane(values + W * k.joint[l]);
      const float* d = k.d + 3 * l;
      for (int i = 0; i < 3; ++i) m[9 + i] = m[9 + i] + q * L::splat(d[i]);
    }
    float* pose = links + static_cast<std::ptrdiff_t>(12 * W) * l;
    if (k.parent[l] < 0) {
      for (int i = 0; i < 12; ++i) m[i].store(pose + W * i);
      continue;
    }
    // The link's pose: its parent's composed with M.
    const float* up = links + static_cast<std::ptrdiff_t>(12 * W) * k.parent[l];
    L p[12];
    for (int i = 0; i < 12; ++i) p[i] = lane(up + W * i);
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col) {
        const L v = p[3 * r] * m[col] + p[3 * r + 1] * m[3 + col] + p[3 * r + 2] * m[6 + col];
        v.store(pose + W * (3 * r + col));
      }
      const L v = p[3 * r] * m[9] + p[3 * r + 1] * m[10] + p[3 * r + 2] * m[11] + p[9 + r];
      v.store(pose + W * (9 + r));
    }
  }
  if (boxes != nullptr) {
    // Each boxed link's box: about its centre's place, |R| times the half extents (each corner of
    // the box in the link's frame lies within it); the margin, a hundred-thousandth of every
    // term's size, is far more than a few roundings of each and of the spheres' own placing.
    const L zero = L::splat(0.0f);
    for (int l = 0; l < k.boxed_links; ++l) {
      const float* pose = links + static_cast<std::ptrdiff_t>(12 * W) * l;
      const float* c = k.box_centre + 3 * l;
      const float* size = k.box_centre_size + 3 * l;
      const float* h = k.box_half + 3 * l;
      float* box = boxes + static_cast<std::ptrdiff_t>(6 * W) * l;
      for (int r = 0; r < 3; ++r) {
        const L p0 = lane(pose + W * (3 * r));
        const L p1 = lane(pose + W * (3 * r + 1));
        const L p2 = lane(pose + W * (3 * r + 2));
        const L t = lane(pose + W * (9 + r));
        const L a0 = max(p0, zero - p0);
        const L a1 = max(p1, zero - p1);
        const L a2 = max(p2, zero - p2);
        const L centre = p0 * L::splat(c[0]) + p1 * L::splat(c[1]) + p2 * L::splat(c[2]) + t;
        const L half = a0 * L::splat(h[0]) + a1 * L::splat(h[1]) + a2 * L::splat(h[2]);
        const L margin = L::splat(1e-5f) * (max(t, zero - t) + half + a0 * L::splat(size[0]) +
                                            a1 * L::splat(size[1]) + a2 * L::splat(size[2]));
        (centre - half - margin).store(box + W * r);
        (centre + half + margin).store(box + W * (3 + r));
      }
    }
  }
  if (out == nullptr) return;  // the links' poses alone
  float* lanes_out[W];
  for (int i = 0; i < W; ++i) lanes_out[i] = out + 4 * static_cast<std::ptrdiff_t>(k.spheres) * i;
  for (int s = 0; s < k.spheres; ++s) place_sphere<L>(k, links, s, lanes_out);
}
