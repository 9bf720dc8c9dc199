#include "sphys/tools/tree_cache.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/tools/primitives.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

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

void overwrite(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// The offset of a .sph text's header line "3 8" (depth 3, branching 8) in a cache entry.
std::size_t sph_header(const std::string& entry) {
  const std::size_t at = entry.find("3 8\n");
  EXPECT_NE(at, std::string::npos) << "no .sph header line in the entry";
  return at;
}

// The offset of the radius, the fourth number, on the entry's last line of a used sphere (a
// leaf; unused slots have radius -1).
std::size_t last_radius(const std::string& entry) {
  std::size_t end = entry.size() - 1;
  while (true) {
    const std::size_t start = entry.rfind('\n', end - 1) + 1;
    std::size_t at = start;
    for (int field = 0; field < 3; ++field) at = entry.find(' ', at) + 1;
    if (entry[at] != '-') return at;
    end = start - 1;
  }
}

// A cache entry damaged on purpose: the tree is built and cached, `damage` changes its bytes,
// then the same request must rebuild the very same tree, say so naming the entry, and leave the
// clean entry in place.
void expect_rebuilt_after(const std::function<void(std::string&)>& damage) {
  const test::TempDir dir;
  const TriangleMesh torus = make_torus(1.0, 0.3, 24, 12);
  const CachedTree clean = build_sphere_tree_cached(torus, octree(3), dir.path());
  ASSERT_EQ(clean.tree.depth(), 3);
  const fs::path entry = cache_path(dir.path(), torus, octree(3));
  const std::string clean_bytes = test::read_whole(entry);
  std::string damaged = clean_bytes;
  damage(damaged);
  ASSERT_NE(damaged, clean_bytes);
  overwrite(entry, damaged);

  testing::internal::CaptureStderr();
  const CachedTree again = build_sphere_tree_cached(torus, octree(3), dir.path());
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(again.from_cache);
  EXPECT_EQ(again.tree, clean.tree);
  EXPECT_THAT(err, testing::StartsWith("sphys: note: " + entry.string() +
                                       ": a damaged sphere-tree cache entry ("));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(test::read_whole(entry), clean_bytes);
  EXPECT_TRUE(build_sphere_tree_cached(torus, octree(3), dir.path()).from_cache);
}

// The case: depth 3 became 2, and a 9-sphere tree was used where 73 were asked for.
TEST(TreeCache, EntryWithAChangedHeaderByteIsRebuilt) {
  expect_rebuilt_after([](std::string& bytes) { bytes[sph_header(bytes)] = '2'; });
}

TEST(TreeCache, EntryWithAChangedRadiusIsRebuilt) {
  expect_rebuilt_after([](std::string& bytes) {
    const std::size_t radius = last_radius(bytes);
    const std::size_t digit = bytes.find_first_of("12345678", radius);
    ASSERT_LT(digit, bytes.find(' ', radius));
    ++bytes[digit];
  });
}

TEST(TreeCache, EntryCutInsideItsLastRadiusIsRebuilt) {
  expect_rebuilt_after([](std::string& bytes) { bytes.resize(last_radius(bytes) + 3); });
}

TEST(TreeCache, AnotherMeshsEntryRenamedOntoTheKeyIsRebuilt) {
  const test::TempDir other;
  const TriangleMesh box = make_box({1, 2, 3});
  (void)build_sphere_tree_cached(box, octree(3), other.path());
  const std::string box_entry = test::read_whole(cache_path(other.path(), box, octree(3)));
  expect_rebuilt_after([&](std::string& bytes) { bytes = box_entry; });
}

// Running as root, a folder of mode 000 is still readable: a path through a file fails for
// everyone. The command-line suite covers permissions (tests/apps/faults_command_test.cpp).
TEST(TreeCache, UnusableFolderBuildsWithOneNote) {
  const test::TempDir dir;
  const fs::path blocked = dir.write("blocked", "a file where the cache folder should be");
  const TriangleMesh box = make_box({1, 2, 3});
  testing::internal::CaptureStderr();
  const CachedTree first = build_sphere_tree_cached(box, octree(2), blocked / "cache");
  const CachedTree second = build_sphere_tree_cached(box, octree(2), blocked / "cache");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(first.from_cache);
  EXPECT_FALSE(second.from_cache);
  EXPECT_EQ(first.tree, build_sphere_tree(box, octree(2)));
  EXPECT_EQ(err, "sphys: note: the sphere-tree cache " + (blocked / "cache").string() +
                     " cannot be used (Not a directory); going on without it\n");
}

TEST(TreeCache, CheckNamesTheDamagedEntriesAndClearEmptiesTheFolder) {
  const test::TempDir dir;
  const TriangleMesh box = make_box({1, 2, 3});
  (void)build_sphere_tree_cached(box, octree(2), dir.path());
  (void)build_sphere_tree_cached(box, octree(3), dir.path());
  const fs::path damaged = cache_path(dir.path(), box, octree(3));
  std::string bytes = test::read_whole(damaged);
  bytes[sph_header(bytes)] = '2';
  overwrite(damaged, bytes);
  // An entry of the versions whose entries were plain .sph files, and files of the user's.
  const fs::path plain = dir.write("octree-b8-d3-fedcba9876543210.sph", "1 8\n0 0 0 1 1\n");
  dir.write("notes.txt", "not an entry");
  dir.write("mine.sph", "1 8\n0 0 0 1 1\n");

  const std::vector<CacheEntryCheck> checks = check_cache(dir.path());
  ASSERT_EQ(checks.size(), 3u);
  EXPECT_EQ(checks[0].path, cache_path(dir.path(), box, octree(2)));
  EXPECT_FALSE(checks[0].problem);
  EXPECT_EQ(checks[0].description, "octree, branching 8, depth 2 (9 spheres)");
  EXPECT_EQ(checks[1].path, damaged);
  EXPECT_EQ(checks[1].problem, "its checksum does not match its bytes (changed or cut short)");
  EXPECT_EQ(checks[2].path, plain);
  EXPECT_THAT(checks[2].problem.value_or(""),
              testing::StartsWith("not a sphere-tree cache entry of this sphys"));

  EXPECT_EQ(clear_cache(dir.path()), 3u);
  EXPECT_TRUE(check_cache(dir.path()).empty());
  EXPECT_TRUE(fs::exists(dir.path() / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir.path() / "mine.sph"));
}

}  // namespace
}  // namespace sphys::tools
