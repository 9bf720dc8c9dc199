// The descent's child test over a float lane type F of kChildLanes lanes (core/simd.h). Included
// inside an anonymous namespace by each file that instantiates it (child_test_lanes.cpp,
// child_test_lanes_avx2.cpp), so that no instance compiled for AVX2 can stand in for another.
// Each sum is grouped as Eigen's fixed-size float products group it (a + (b + c) for a row of
// R c and for |d|²), so that the lanes give the bits of the one-pair test they replaced.

namespace child_lanes {

template <class F>
ChildHits test_children(const PosedColumns& tree, std::uint32_t first, const OtherNode& other) {
  const F x = F::load_unaligned(tree.x + first);
  const F y = F::load_unaligned(tree.y + first);
  const F z = F::load_unaligned(tree.z + first);
  const float* r = tree.rotation;
  const F wx = (F::splat(r[0]) * x + (F::splat(r[3]) * y + F::splat(r[6]) * z)) +
               F::splat(tree.translation[0]);
  const F wy = (F::splat(r[1]) * x + (F::splat(r[4]) * y + F::splat(r[7]) * z)) +
               F::splat(tree.translation[1]);
  const F wz = (F::splat(r[2]) * x + (F::splat(r[5]) * y + F::splat(r[8]) * z)) +
               F::splat(tree.translation[2]);
  wx.store_unaligned(tree.world_x + first);
  wy.store_unaligned(tree.world_y + first);
  wz.store_unaligned(tree.world_z + first);

  const F dx = wx - F::splat(other.center[0]);
  const F dy = wy - F::splat(other.center[1]);
  const F dz = wz - F::splat(other.center[2]);
  const F distance_squared = dx * dx + (dy * dy + dz * dz);
  const F radius = F::load_unaligned(tree.radius + first);
  const F margin = F::splat(other.margin);
  const F slack = F::splat(other.slack);
  const F other_bound = F::splat(other.bound);
  const F leaf_reach = (radius + F::splat(other.radius)) + margin;
  const F leaf_bound = ((radius + other_bound) + margin) * slack;
  const F subtree_bound =
      ((F::load_unaligned(tree.subtree_radius + first) + other_bound) + margin) * slack;
  return {bits(distance_squared <= leaf_reach * leaf_reach),
          bits(distance_squared <= leaf_bound * leaf_bound),
          bits(distance_squared <= subtree_bound * subtree_bound)};
}

}  // namespace child_lanes
