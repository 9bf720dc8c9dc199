#include "sphys/tools/build_tree.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/mesh_query.h"
#include "sphys/tools/model.h"
#include "sphys/tools/primitives.h"
#include "sphys/tools/tree_quality.h"
#include "support/level_coverage.h"
#include "support/sanitized_run.h"

namespace sphys::tools {
namespace {

using test::uncovered_points;

constexpr BuildMethod kAllMethods[] = {
    BuildMethod::Octree,  BuildMethod::Grid,     BuildMethod::Spawn,
    BuildMethod::Hubbard, BuildMethod::Merge,    BuildMethod::Burst,
    BuildMethod::Expand,  BuildMethod::Combined, BuildMethod::Tight};

struct Subject {
  std::string name;
  TriangleMesh mesh;
};

std::vector<Subject> subjects() {
  if (test::sanitized_run()) return {{"torus", make_torus(1.0, 0.3, 32, 16)}};
  return {{"cube", make_box({1, 1, 1})},
          {"torus", make_torus(1.0, 0.3, 32, 16)},
          {"plate", make_box({1, 0.05, 1})},
          {"bunny", load_model("bunny")}};
}

class EveryMethod : public testing::TestWithParam<BuildMethod> {};

TEST_P(EveryMethod, EveryLevelCoversTheWholeSurface) {
  for (const Subject& subject : subjects()) {
    BuildOptions options;
    options.method = GetParam();
    options.depth = 3;
    const SphereTree tree = build_sphere_tree(subject.mesh, options);
    EXPECT_EQ(tree.depth(), 3) << subject.name;
    EXPECT_EQ(tree.branching(), 8);
    for (std::uint32_t node = 0; node < tree.size(); ++node) {
      EXPECT_LE(tree.child_count(node), 8u);
    }
    const MeshQuery query(subject.mesh);
    QualityOptions quality;
    quality.volume_samples = 20000;
    const std::vector<LevelQuality> levels = measure_tree(tree, query, quality);
    for (int level = 0; level < tree.depth(); ++level) {
      EXPECT_EQ(uncovered_points(tree, level, subject.mesh), 0u)
          << subject.name << " level " << level;
      EXPECT_EQ(levels[static_cast<std::size_t>(level)].coverage, 1.0)
          << subject.name << " level " << level;
    }
  }
}

TEST_P(EveryMethod, SameSeedSameTree) {
  BuildOptions options;
  options.method = GetParam();
  options.depth = 2;
  options.seed = 42;
  const TriangleMesh torus = make_torus(1.0, 0.3, 24, 12);
  EXPECT_EQ(build_sphere_tree(torus, options), build_sphere_tree(torus, options));
}

INSTANTIATE_TEST_SUITE_P(BuildTree, EveryMethod, testing::ValuesIn(kAllMethods),
                         [](const testing::TestParamInfo<BuildMethod>& param_info) {
                           return std::string(method_name(param_info.param));
                         });

// The paper's configuration against the simplest one, on the default bunny.
TEST(BuildTree, CombinedIsTighterThanOctreeOnTheBunny) {
  const TriangleMesh bunny = load_model("bunny");
  const MeshQuery query(bunny);
  for (int depth : {2, 3}) {
    BuildOptions options;
    options.depth = depth;
    options.method = BuildMethod::Octree;
    const LevelQuality octree = measure_tree(build_sphere_tree(bunny, options), query).back();
    options.method = BuildMethod::Combined;
    const LevelQuality combined = measure_tree(build_sphere_tree(bunny, options), query).back();
    EXPECT_LT(combined.outside_volume, octree.outside_volume) << "depth " << depth;
    EXPECT_LT(combined.worst_protrusion, octree.worst_protrusion) << "depth " << depth;
  }
}

TEST(BuildTree, RejectsImpossibleOptions) {
  const TriangleMesh cube = make_box({1, 1, 1});
  BuildOptions options;
  options.branching = 1;
  EXPECT_THROW((void)build_sphere_tree(cube, options), Error);
  options.branching = 9;
  EXPECT_THROW((void)build_sphere_tree(cube, options), Error);
  options.branching = 8;
  options.depth = 0;
  EXPECT_THROW((void)build_sphere_tree(cube, options), Error);
  options.depth = 3;
  options.branching = 4;
  options.method = BuildMethod::Octree;
  EXPECT_THROW((void)build_sphere_tree(cube, options), Error);
  EXPECT_THROW((void)build_sphere_tree(TriangleMesh{}, BuildOptions{}), Error);
}

TEST(BuildTree, MethodNamesRoundTripAndUnknownNamesAreListed) {
  for (BuildMethod method : kAllMethods) EXPECT_EQ(parse_method(method_name(method)), method);
  try {
    (void)parse_method("voronoi");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("unknown sphere-tree method 'voronoi'"));
    EXPECT_THAT(e.what(), testing::HasSubstr("combined"));
  }
}

TEST(BuildTree, SmallerBranchingFactors) {
  const TriangleMesh torus = make_torus(1.0, 0.3, 32, 16);
  for (int branching : {2, 4}) {
    BuildOptions options;
    options.method = BuildMethod::Merge;
    options.branching = branching;
    options.depth = 3;
    const SphereTree tree = build_sphere_tree(torus, options);
    for (std::uint32_t node = 0; node < tree.size(); ++node) {
      EXPECT_LE(tree.child_count(node), static_cast<std::uint32_t>(branching));
    }
    for (int level = 0; level < tree.depth(); ++level) {
      EXPECT_EQ(uncovered_points(tree, level, torus), 0u);
    }
  }
}

}  // namespace
}  // namespace sphys::tools
