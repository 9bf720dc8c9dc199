#include "sphys/tools/sph_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using sphys::test::files_in;
using sphys::test::read_whole;
using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::IsEmpty;
using testing::StartsWith;

SphereTree read_text(const std::string& text, const SphReadOptions& options = {}) {
  std::istringstream in(text);
  return read_sph(in, "t.sph", options);
}

std::string written(const SphereTree& tree) {
  std::ostringstream out;
  write_sph(out, tree);
  return out.str();
}

// The message of the Error that reading `text` as "t.sph" throws.
std::string read_error(const std::string& text, const SphReadOptions& options = {}) {
  try {
    (void)read_text(text, options);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

std::vector<std::int32_t> parents_of(const SphereTree& tree) {
  std::vector<std::int32_t> parents;
  for (std::uint32_t i = 0; i < tree.size(); ++i) parents.push_back(tree.parent(i));
  return parents;
}

// A random tree of exactly `depth` levels: every node gets 0..B children, except that the first
// node of each level gets at least one so that the last level is reached.
SphereTree random_tree(std::mt19937& rng, int branching, int depth) {
  std::uniform_real_distribution<float> coordinate(-100.0f, 100.0f);
  std::uniform_real_distribution<float> radius(1e-3f, 50.0f);
  std::uniform_int_distribution<int> children(0, branching);
  std::vector<SphereTreeNode> nodes{
      {{Vec3(coordinate(rng), coordinate(rng), coordinate(rng)), radius(rng)}, -1}};
  std::size_t level_begin = 0;
  for (int level = 1; level < depth; ++level) {
    const std::size_t level_end = nodes.size();
    for (std::size_t parent = level_begin; parent < level_end; ++parent) {
      const int count = parent == level_begin ? std::max(1, children(rng)) : children(rng);
      for (int c = 0; c < count; ++c) {
        nodes.push_back({{Vec3(coordinate(rng), coordinate(rng), coordinate(rng)), radius(rng)},
                         static_cast<std::int32_t>(parent)});
      }
    }
    level_begin = level_end;
  }
  return SphereTree::from_nodes(nodes, branching);
}

TEST(SphFile, RandomTreesRoundTripExactly) {
  std::mt19937 rng(20240611);
  for (int branching = 2; branching <= 8; ++branching) {
    for (int depth = 1; depth <= 4; ++depth) {
      for (int trial = 0; trial < 3; ++trial) {
        const SphereTree tree = random_tree(rng, branching, depth);
        ASSERT_EQ(tree.depth(), depth);
        const SphereTree back = read_text(written(tree));
        EXPECT_EQ(back, tree) << "branching " << branching << ", depth " << depth;
        EXPECT_EQ(back.depth(), depth);
      }
    }
  }
}

TEST(SphFile, ExtremeFloatsRoundTripExactly) {
  const float max = std::numeric_limits<float>::max();
  const float tiny = std::numeric_limits<float>::denorm_min();
  const std::vector<SphereTreeNode> nodes = {
      {{Vec3(max, -max, 0.1f), max}, -1},
      {{Vec3(tiny, -tiny, -0.0f), tiny}, 0},
      {{Vec3(1.0f / 3.0f, std::nextafter(1.0f, 2.0f), 123456789.0f),
        std::numeric_limits<float>::min()},
       0},
  };
  const SphereTree tree = SphereTree::from_nodes(nodes, 2);
  EXPECT_EQ(read_text(written(tree)), tree);
}

// Any finite float from its bits, magnitudes of 1e-45 to 3e38 alike.
float random_finite_float(std::mt19937& rng) {
  for (;;) {
    const float value = std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
    if (std::isfinite(value)) return value;
  }
}

TEST(SphFile, ArbitraryFiniteFloatsRoundTripExactly) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    // A complete tree of 4 levels of branching 8: 585 spheres.
    std::vector<SphereTreeNode> nodes;
    for (std::int32_t i = 0; i < 585; ++i) {
      float radius = 0.0f;
      while (radius == 0.0f) radius = std::abs(random_finite_float(rng));
      nodes.push_back(
          {{Vec3(random_finite_float(rng), random_finite_float(rng), random_finite_float(rng)),
            radius},
           i == 0 ? -1 : (i - 1) / 8});
    }
    const SphereTree tree = SphereTree::from_nodes(nodes, 8);
    EXPECT_EQ(read_text(written(tree)), tree);
  }
}

TEST(SphFile, WritesTheCompleteTreeWithUnusedSlots) {
  // Root; two children; the second child has one child.
  const std::vector<SphereTreeNode> nodes = {{{Vec3(0, 0, 0), 4}, -1},
                                             {{Vec3(-2, 0, 0), 2}, 0},
                                             {{Vec3(2, 0.5f, 0), 2.5f}, 0},
                                             {{Vec3(2, 0, -1), 0.1f}, 2}};
  EXPECT_EQ(written(SphereTree::from_nodes(nodes, 2)),
            "3 2\n"
            "0 0 0 4 1\n"
            "-2 0 0 2 1\n"
            "2 0.5 0 2.5 1\n"
            "0 0 0 -1 1\n"
            "0 0 0 -1 1\n"
            "2 0 -1 0.100000001 1\n"
            "0 0 0 -1 1\n");
}

// Levels 3, branching 2, as the toolkit writes it: unused slots with a negative radius and
// garbage centres, a node with the auxiliary sphere fields, then the options and evaluation.
constexpr const char* kToolkitFile =
    "3 2\n"
    "0.000000 0.000000 0.000000 2.000000 1.000000\n"
    "-1.000000 0.000000 0.000000 1.200000 0.900000\n"
    "1.000000 0.250000 0.000000 1.100000 0.800000 1.000000 0.000000 0.000000 1.050000 0.050000\n"
    "-1.500000 0.500000 0.000000 0.600000 1.000000\n"
    "-0.500000 -0.500000 0.000000 0.550000 1.000000\n"
    "123456792.000000 -98765.429688 100000002004087734272.000000 -0.000001 0.000000\n"
    "nan -inf 0.000000 -1.000000 1.000000\n"
    "\n"
    "\n"
    "Options : \n"
    "    Algorithm : Medial\n"
    "    Depth : 3\n"
    "    Branching : 2\n"
    "\n"
    "Evaluation : \n"
    "    Level 0 : worst error 0.123\n";

TEST(SphFile, ReadsTheToolkitLayout) {
  const SphereTree tree = read_text(kToolkitFile);
  EXPECT_EQ(tree.branching(), 2);
  EXPECT_EQ(tree.depth(), 3);
  ASSERT_EQ(tree.size(), 5u);
  EXPECT_THAT(parents_of(tree), ElementsAre(-1, 0, 0, 1, 1));
  EXPECT_EQ(tree.sphere(0).center, Vec3(0, 0, 0));
  EXPECT_EQ(tree.sphere(0).radius, 2.0f);
  EXPECT_EQ(tree.sphere(1).center, Vec3(-1, 0, 0));
  EXPECT_EQ(tree.sphere(1).radius, 1.2f);
  EXPECT_EQ(tree.sphere(2).center, Vec3(1, 0.25f, 0));
  EXPECT_EQ(tree.sphere(2).radius, 1.1f);
  EXPECT_EQ(tree.sphere(3).center, Vec3(-1.5f, 0.5f, 0));
  EXPECT_EQ(tree.sphere(3).radius, 0.6f);
  EXPECT_EQ(tree.sphere(4).center, Vec3(-0.5f, -0.5f, 0));
  EXPECT_EQ(tree.sphere(4).radius, 0.55f);
  EXPECT_TRUE(tree.is_leaf(2));
}

TEST(SphFile, ReadsBranchingFourWithBlankLinesCrLfAndFourFieldLines) {
  std::string text = "2 4\r\n\r\n0 0 0 3\r\n1 0 0 1 1\r\n\r\n-1 0 0 1 1\r\n";
  text += "5 5 5 -1 1\r\n5 5 5 -1 1\r\n";
  const SphereTree tree = read_text(text);
  EXPECT_EQ(tree.branching(), 4);
  EXPECT_EQ(tree.depth(), 2);
  EXPECT_THAT(parents_of(tree), ElementsAre(-1, 0, 0));
  EXPECT_EQ(tree.sphere(2).center, Vec3(-1, 0, 0));
}

TEST(SphFile, BottomLevelsWithoutUsedSpheresAreDropped) {
  // Four levels in the header, but levels 2 and 3 hold no used sphere.
  std::string text = "4 2\n0 0 0 2 1\n1 0 0 1 1\n-1 0 0 1 1\n";
  for (int i = 0; i < 4 + 8; ++i) text += "0 0 0 -0.000001 1\n";
  const SphereTree tree = read_text(text);
  EXPECT_EQ(tree.depth(), 2);
  EXPECT_EQ(tree.size(), 3u);
  EXPECT_THAT(written(tree), StartsWith("2 2\n"));
}

TEST(SphFile, ASingleLevelIsJustTheRoot) {
  const SphereTree tree = read_text("1 8\n1 2 3 4 1\n");
  EXPECT_EQ(tree.size(), 1u);
  EXPECT_EQ(tree.root().center, Vec3(1, 2, 3));
  EXPECT_EQ(written(tree), "1 8\n1 2 3 4 1\n");
}

TEST(SphFile, ShiftIsAddedToEveryCentre) {
  SphReadOptions options;
  options.shift = Vec3d(10, -20, 0.5);
  const SphereTree tree = read_text(kToolkitFile, options);
  ASSERT_EQ(tree.size(), 5u);
  EXPECT_EQ(tree.sphere(0).center, Vec3(10, -20, 0.5f));
  EXPECT_EQ(tree.sphere(2).center, Vec3(11, -19.75f, 0.5f));
  EXPECT_EQ(tree.sphere(4).center, Vec3(9.5f, -20.5f, 0.5f));
  EXPECT_EQ(tree.sphere(4).radius, 0.55f);  // radii are not shifted
}

TEST(SphFile, ShiftMustBeFinite) {
  SphReadOptions options;
  options.shift = Vec3d(0, std::numeric_limits<double>::quiet_NaN(), 0);
  EXPECT_THAT(read_error(kToolkitFile, options),
              AllOf(StartsWith("t.sph: "), HasSubstr("shift"), HasSubstr("not finite")));
}

TEST(SphFile, ReadsFromAPath) {
  const test::TempDir dir;
  const fs::path file = dir.write("tree.sph", kToolkitFile);
  EXPECT_EQ(read_sph(file), read_text(kToolkitFile));
}

// --- Malformed input: every message names the file, the line and the problem. ---

TEST(SphFileErrors, MissingFile) {
  const test::TempDir dir;
  try {
    (void)read_sph(dir.path() / "absent.sph");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), AllOf(HasSubstr("absent.sph: "), HasSubstr("no such file")));
  }
}

TEST(SphFileErrors, Directory) {
  const test::TempDir dir;
  try {
    (void)read_sph(dir.path());
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("is a directory"));
  }
}

TEST(SphFileErrors, EmptyFile) {
  EXPECT_THAT(read_error(""), AllOf(StartsWith("t.sph:1: "), HasSubstr("file is empty")));
  EXPECT_THAT(read_error("\n  \n"), AllOf(StartsWith("t.sph:1: "), HasSubstr("file is empty")));
}

TEST(SphFileErrors, HeaderWithOneNumber) {
  EXPECT_THAT(read_error("\n3\r\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("two integers"), HasSubstr("got '3'")));
}

TEST(SphFileErrors, HeaderNotIntegers) {
  EXPECT_THAT(read_error("3.5 2\n"), AllOf(StartsWith("t.sph:1: "), HasSubstr("two integers")));
  EXPECT_THAT(read_error("three 2\n"), AllOf(StartsWith("t.sph:1: "), HasSubstr("two integers")));
}

TEST(SphFileErrors, HeaderWithAThirdField) {
  EXPECT_THAT(read_error("3 2 7\n"), AllOf(StartsWith("t.sph:1: "), HasSubstr("two integers")));
}

TEST(SphFileErrors, LevelsBelowOne) {
  EXPECT_THAT(read_error("0 2\n"), AllOf(StartsWith("t.sph:1: "),
                                         HasSubstr("levels must be at least 1 (the root), got 0")));
  EXPECT_THAT(read_error("-99999999999999999999 2\n"),
              AllOf(StartsWith("t.sph:1: "), HasSubstr("levels must be at least 1")));
}

TEST(SphFileErrors, BranchingOutsideTwoToEight) {
  EXPECT_THAT(read_error("2 1\n0 0 0 1\n"),
              AllOf(StartsWith("t.sph:1: "), HasSubstr("branching factor 1 is below 2")));
  EXPECT_THAT(read_error("2 9\n"),
              AllOf(StartsWith("t.sph:1: "), HasSubstr("branching factor 9 is above 8, the most a "
                                                       "sphere-tree may have")));
}

TEST(SphFileErrors, AbsurdlyManyLevels) {
  EXPECT_THAT(read_error("40 2\n0 0 0 1 1\n"),
              AllOf(StartsWith("t.sph:1: "), HasSubstr("40 levels with branching 2"),
                    HasSubstr("more than 10000000 node lines")));
  EXPECT_THAT(read_error("99999999999999999999 8\n"),
              AllOf(StartsWith("t.sph:1: "), HasSubstr("more than 10000000 node lines")));
}

TEST(SphFileErrors, FieldThatIsNotANumber) {
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\n0 0 zero 1 1\n"),
              AllOf(StartsWith("t.sph:3: "), HasSubstr("z is not a number: 'zero'")));
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\n0 0 0 1 1\n1,5 0 0 -1 1\n"),
              AllOf(StartsWith("t.sph:4: "), HasSubstr("x is not a number: '1,5'")));
}

TEST(SphFileErrors, NumberOutsideTheRangeOfADouble) {
  EXPECT_THAT(read_error("1 2\n0 1e999 0 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("y '1e999' is outside the range")));
}

TEST(SphFileErrors, FewerThanFourFields) {
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\n0 0 1\n"),
              AllOf(StartsWith("t.sph:3: "), HasSubstr("at least 4 numbers"), HasSubstr("got 3")));
}

TEST(SphFileErrors, NonFiniteCentreOfAUsedSphere) {
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\n0 nan 0 1 1\n"),
              AllOf(StartsWith("t.sph:3: "), HasSubstr("y of a used sphere is not finite: 'nan'")));
  EXPECT_THAT(read_error("1 2\n-inf 0 0 1 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("x of a used sphere is not finite")));
}

TEST(SphFileErrors, InfiniteRadius) {
  EXPECT_THAT(read_error("1 2\n0 0 0 inf 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("radius of a used sphere is not finite")));
}

TEST(SphFileErrors, NanRadiusEvenInAnUnusedPosition) {
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\n0 0 0 1 1\n0 0 0 nan 1\n"),
              AllOf(StartsWith("t.sph:4: "), HasSubstr("radius is NaN")));
}

TEST(SphFileErrors, UsedSphereOutsideSinglePrecision) {
  EXPECT_THAT(read_error("1 2\n0 0 1e39 1 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("z '1e39' does not fit in single")));
  EXPECT_THAT(read_error("1 2\n0 0 0 1e-50 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("rounds to zero in single precision")));
}

TEST(SphFileErrors, UsedSphereUnderAnUnusedParent) {
  // Slot 4 (line 6) is a child of slot 1 (line 3), which is unused.
  EXPECT_THAT(read_error("3 2\n0 0 0 2 1\n0 0 0 -1 1\n0 0 0 -1 1\n0 0 0 -1 1\n0 0 0 1 1\n"),
              AllOf(StartsWith("t.sph:6: "), HasSubstr("under an unused parent (line 3)")));
}

TEST(SphFileErrors, UnusedRoot) {
  EXPECT_THAT(read_error("2 2\n0 0 0 -1 1\n0 0 0 -1 1\n0 0 0 -1 1\n"),
              AllOf(StartsWith("t.sph:2: "), HasSubstr("root sphere is unused")));
}

TEST(SphFileErrors, TruncatedFile) {
  // Levels 3 with branching 2 need 7 node lines; the file has 5, so line 7 is node line 6.
  EXPECT_THAT(read_error("3 2\n0 0 0 2 1\n0 0 0 1 1\n0 0 0 1 1\n0 0 0 0.5 1\n0 0 0 -1 1\n"),
              AllOf(StartsWith("t.sph:7: "), HasSubstr("file ends early"),
                    HasSubstr("need 7 node lines"), HasSubstr("node line 6 is missing")));
}

TEST(SphFileErrors, TextWhereANodeLineBelongs) {
  EXPECT_THAT(read_error("2 2\n0 0 0 2 1\nOptions : \n"),
              AllOf(StartsWith("t.sph:3: "), HasSubstr("not a number: 'Options'")));
}

// --- Writing files. ---

TEST(SphFileWrite, WritesAndReadsBackAFile) {
  const test::TempDir dir;
  const SphereTree tree = read_text(kToolkitFile);
  const fs::path file = dir.path() / "tree.sph";
  write_sph(file, tree);
  EXPECT_EQ(read_whole(file), written(tree));
  EXPECT_EQ(read_sph(file), tree);
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(SphFileWrite, ReplacesAnExistingFileWhole) {
  const test::TempDir dir;
  const fs::path file = dir.write("tree.sph", std::string(100000, 'x'));
  const SphereTree tree = read_text("1 2\n1 2 3 4 1\n");
  write_sph(file, tree);
  EXPECT_EQ(read_whole(file), "1 2\n1 2 3 4 1\n");
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(SphFileWrite, MissingDirectoryThrowsAndLeavesNothingBehind) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "absent" / "tree.sph";
  try {
    write_sph(file, read_text("1 2\n1 2 3 4 1\n"));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(),
                AllOf(HasSubstr("tree.sph: "), HasSubstr("the directory does not exist")));
  }
  EXPECT_FALSE(fs::exists(dir.path() / "absent"));
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(SphFileWrite, EmptyTreeIsRefused) {
  std::ostringstream out;
  EXPECT_THROW(write_sph(out, SphereTree()), Error);
  EXPECT_EQ(out.str(), "");
}

TEST(SphFileWrite, TreeTooDeepForACompleteLayoutIsRefusedBeforeWriting) {
  // A chain of 25 spheres: 25 levels of branching 2 need 2^25 - 1 slots.
  std::vector<SphereTreeNode> chain(25);
  for (std::int32_t i = 0; i < 25; ++i)
    chain[static_cast<std::size_t>(i)] = {{Vec3(0, 0, 0), 1}, i - 1};
  const SphereTree tree = SphereTree::from_nodes(chain, 2);
  std::ostringstream out;
  try {
    write_sph(out, tree);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("more than 10000000 node lines"));
  }
  EXPECT_EQ(out.str(), "");

  const test::TempDir dir;
  EXPECT_THROW(write_sph(dir.path() / "deep.sph", tree), Error);
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

}  // namespace
}  // namespace sphys::tools
