#include "sphys/tools/tree_cache.h"

#include <gtest/gtest.h>

#include "sphys/tools/primitives.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

BuildOptions octree(int depth) {
  BuildOptions options;
  options.method = BuildMethod::Octree;
  options.depth = depth;
  return options;
}

TEST(TreeCache, SecondBuildComesFromTheCacheUnchanged) {
  const test::TempDir dir;
  const TriangleMesh torus = make_torus(1.0, 0.3, 24, 12);
  const CachedTree first = build_sphere_tree_cached(torus, octree(3), dir.path());
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(std::filesystem::exists(cache_path(dir.path(), torus, octree(3))));
  const CachedTree second = build_sphere_tree_cached(torus, octree(3), dir.path());
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.tree, first.tree);
}

TEST(TreeCache, KeyedByMeshContentAndParameters) {
  const test::TempDir dir;
  const TriangleMesh torus = make_torus(1.0, 0.3, 24, 12);
  TriangleMesh moved = torus;
  moved.vertices[0].x() += 1e-9;
  BuildOptions seeded = octree(3);
  seeded.seed = 2;
  const auto path = cache_path(dir.path(), torus, octree(3));
  EXPECT_NE(path, cache_path(dir.path(), moved, octree(3)));
  EXPECT_NE(path, cache_path(dir.path(), torus, octree(2)));
  EXPECT_NE(path, cache_path(dir.path(), torus, seeded));
  EXPECT_EQ(path, cache_path(dir.path(), make_torus(1.0, 0.3, 24, 12), octree(3)));
}

TEST(TreeCache, DamagedEntryIsRebuilt) {
  const test::TempDir dir;
  const TriangleMesh box = make_box({1, 2, 3});
  const auto path = cache_path(dir.path(), box, octree(2));
  dir.write(path.filename().string(), "2 8\n0 0 0 garbage\n");
  const CachedTree tree = build_sphere_tree_cached(box, octree(2), dir.path());
  EXPECT_FALSE(tree.from_cache);
  EXPECT_EQ(tree.tree.depth(), 2);
  EXPECT_TRUE(build_sphere_tree_cached(box, octree(2), dir.path()).from_cache);
}

}  // namespace
}  // namespace sphys::tools
