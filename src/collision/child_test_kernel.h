// The descent's child test over a float lane type F of kChildLanes lanes (core/simd.h). Included
// inside an anonymous namespace by each file that instantiates it (child_test_lanes.cpp,
// child_test_lanes_avx2.cpp), so that no instance compiled for AVX2 can stand in for another.
// Each sum is grouped as Eigen's fixed-size float products group it (a + (b + c) for a row of
// R c and for |d|²), so that the lanes give the bits of the one-pair test they replaced.

namespace child_lanes {

template <class F>
ChildHits test_children(const ChildTest& test) {
  const F x = F::load_unaligned(test.x);
  const F y = F::load_unaligned(test.y);
  const F z = F::load_unaligned(test.z);
  const float* r = test.rotation;
  const F wx = (F::splat(r[0]) * x + (F::splat(r[3]) * y + F::splat(r[6]) * z)) +
               F::splat(test.translation[0]);
  const F wy = (F::splat(r[1]) * x + (F::splat(r[4]) * y + F::splat(r[7]) * z)) +
               F::splat(test.translation[1]);
  const F wz = (F::splat(r[2]) * x + (F::splat(r[5]) * y + F::splat(r[8]) * z)) +
               F::splat(test.translation[2]);
  wx.store_unaligned(test.world_x);
  wy.store_unaligned(test.world_y);
  wz.store_unaligned(test.world_z);

  const F dx = wx - F::splat(test.other[0]);
  const F dy = wy - F::splat(test.other[1]);
  const F dz = wz - F::splat(test.other[2]);
  const F distance_squared = dx * dx + (dy * dy + dz * dz);
  const F radius = F::load_unaligned(test.radius);
  const F margin = F::splat(test.margin);
  const F slack = F::splat(test.slack);
  const F other_bound = F::splat(test.other_bound);
  const F leaf_reach = (radius + F::splat(test.other_radius)) + margin;
  const F leaf_bound = ((radius + other_bound) + margin) * slack;
  const F subtree_bound = ((F::load_unaligned(test.subtree_radius) + other_bound) + margin) * slack;
  return {bits(distance_squared <= leaf_reach * leaf_reach),
          bits(distance_squared <= leaf_bound * leaf_bound),
          bits(distance_squared <= subtree_bound * subtree_bound)};
}

}  // namespace child_lanes
