#include <algorithm>
#include <cstdint>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/mesh_query.h"
#include "sphys/tools/model.h"
#include "sphys/tools/primitives.h"
#include "support/sanitized_run.h"
#include "tools/build/reducer.h"
#include "tools/build/surface_samples.h"

namespace sphys::tools::build {
namespace {

// Few samples keep the whole binary quick (also under sanitizers); the reducers' work per node
// does not depend on the count beyond their representative cap anyway.
constexpr std::size_t kSampleCount = 3000;

constexpr BuildMethod kMethods[] = {BuildMethod::Grid,     BuildMethod::Spawn, BuildMethod::Hubbard,
                                    BuildMethod::Merge,    BuildMethod::Burst, BuildMethod::Expand,
                                    BuildMethod::Combined, BuildMethod::Tight};

std::string method_label(BuildMethod method) { return std::string(method_name(method)); }

// A mesh with its query structure and samples, built once per shape.
struct Subject {
  explicit Subject(TriangleMesh source)
      : mesh(std::move(source)), query(mesh), samples(sample_surface(mesh, kSampleCount)) {
    all.resize(samples.points.size());
    std::iota(all.begin(), all.end(), 0U);
  }

  [[nodiscard]] BuildContext context(std::uint64_t seed = 1) const {
    return {mesh, query, samples, seed};
  }

  TriangleMesh mesh;
  MeshQuery query;
  SurfaceSamples samples;
  std::vector<std::uint32_t> all;
};

const Subject& subject(const std::string& name) {
  static const Subject cube(make_box({1.0, 1.0, 1.0}));
  static const Subject torus(make_torus(1.0, 0.3, 32, 16));
  static const Subject plate(make_box({1.0, 0.05, 1.0}));
  static const Subject bunny(load_model("bunny"));
  if (name == "cube") return cube;
  if (name == "torus") return torus;
  if (name == "plate") return plate;
  return bunny;
}

// The samples of the first child of a one-ball cover and an eight-ball cover: what the second
// level of a tree hands a reducer.
std::vector<std::uint32_t> first_child(Reducer& reducer, const Subject& s) {
  const Cover top = reducer.cover(s.all, 8);
  return top.samples.front();
}

double worst_error(const Cover& cover, const MeshQuery& query) {
  double worst = 0.0;
  for (const Ball& ball : cover.balls) {
    worst = std::max(worst, ball.radius + query.signed_distance(ball.center));
  }
  return worst;
}

void expect_valid(const Cover& cover, const Subject& s, std::span<const std::uint32_t> input,
                  int max_balls) {
  ASSERT_EQ(cover.balls.size(), cover.samples.size());
  EXPECT_GE(cover.balls.size(), 1U);
  EXPECT_LE(static_cast<int>(cover.balls.size()), max_balls);
  std::vector<std::uint32_t> seen;
  for (std::size_t b = 0; b < cover.balls.size(); ++b) {
    EXPECT_FALSE(cover.samples[b].empty());
    for (const std::uint32_t i : cover.samples[b]) {
      EXPECT_TRUE(cover.balls[b].contains(s.samples.points[i]))
          << "sample " << i << " outside ball " << b;
      seen.push_back(i);
    }
  }
  std::sort(seen.begin(), seen.end());
  std::vector<std::uint32_t> expected(input.begin(), input.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(seen, expected) << "the cover's samples must partition the input";
}

class ReducerTest : public ::testing::TestWithParam<std::tuple<BuildMethod, std::string>> {};

TEST_P(ReducerTest, PartitionsAndContainsTheSamples) {
  const auto& [method, shape] = GetParam();
  if (test::sanitized_run() && shape != "torus") GTEST_SKIP() << "sanitized run: the torus only";
  const Subject& s = subject(shape);
  const BuildContext context = s.context();
  const std::unique_ptr<Reducer> reducer = make_reducer(method, context);
  for (const int max_balls : {1, 8}) {
    SCOPED_TRACE("max_balls " + std::to_string(max_balls));
    expect_valid(reducer->cover(s.all, max_balls), s, s.all, max_balls);
  }
  // A node further down: part of the surface only.
  const std::vector<std::uint32_t> part = first_child(*reducer, s);
  expect_valid(reducer->cover(part, 8), s, part, 8);
}

INSTANTIATE_TEST_SUITE_P(Methods, ReducerTest,
                         ::testing::Combine(::testing::ValuesIn(kMethods),
                                            ::testing::Values("cube", "torus", "plate", "bunny")),
                         [](const ::testing::TestParamInfo<ReducerTest::ParamType>& test) {
                           return method_label(std::get<0>(test.param)) + "_" +
                                  std::get<1>(test.param);
                         });

class CombinedTest : public ::testing::TestWithParam<std::string> {};

// Combined keeps, per node, the best of Merge, Burst and Expand (Bradshaw §4.5).
TEST_P(CombinedTest, NoWorseThanItsParts) {
  if (test::sanitized_run() && GetParam() != "torus")
    GTEST_SKIP() << "sanitized run: the torus only";
  const Subject& s = subject(GetParam());
  const BuildContext context = s.context();
  const double combined =
      worst_error(make_reducer(BuildMethod::Combined, context)->cover(s.all, 8), s.query);
  for (const BuildMethod part : {BuildMethod::Merge, BuildMethod::Burst, BuildMethod::Expand}) {
    const double error = worst_error(make_reducer(part, context)->cover(s.all, 8), s.query);
    EXPECT_LE(combined, error + 1e-12) << method_label(part);
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, CombinedTest,
                         ::testing::Values("cube", "torus", "plate", "bunny"));

TEST(MakeReducer, OctreeHasNone) {
  const Subject& s = subject("cube");
  EXPECT_ANY_THROW(static_cast<void>(make_reducer(BuildMethod::Octree, s.context())));
}

}  // namespace
}  // namespace sphys::tools::build
