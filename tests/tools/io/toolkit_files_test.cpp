// Files in the shapes Bradshaw's Sphere-Tree Construction Toolkit writes, hand-written: unused
// slots (negative radius) anywhere among used siblings, the auxiliary-sphere fields of the medial
// methods, the Options and Evaluation blocks after the tree, and flat sphere sets of more than 8.
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/sph_file.h"

namespace sphys::tools::toolkit_files_test {

using testing::ElementsAre;
using testing::HasSubstr;

SphereTree tree_of(const std::string& text) {
  std::istringstream in(text);
  return read_sph(in, "toolkit.sph");
}

SphSpheres spheres_of(const std::string& text) {
  std::istringstream in(text);
  return read_sph_spheres(in, "toolkit.sph");
}

std::vector<std::int32_t> parents(const SphereTree& tree) {
  std::vector<std::int32_t> result;
  for (std::uint32_t i = 0; i < tree.size(); ++i) result.push_back(tree.parent(i));
  return result;
}

// The tree's shape: branching, depth and each node's parent.
void expect_shape(const SphereTree& tree, int branching, int depth,
                  const std::vector<std::int32_t>& parents_in_order) {
  EXPECT_EQ(tree.branching(), branching);
  EXPECT_EQ(tree.depth(), depth);
  EXPECT_EQ(parents(tree), parents_in_order);
}

std::vector<std::size_t> level_sizes(const SphSpheres& spheres) {
  std::vector<std::size_t> sizes;
  for (const std::vector<Sphere>& level : spheres.levels()) sizes.push_back(level.size());
  return sizes;
}

std::string written(const SphereTree& tree) {
  std::ostringstream out;
  write_sph(out, tree);
  return out.str();
}

// `count` unused slots as the toolkit writes most of them.
std::string unused_slots(int count) {
  std::string lines;
  for (int i = 0; i < count; ++i) lines += "0.000000 0.000000 0.000000 -1.000000 1.000000\n";
  return lines;
}

// An octree output of 3 levels with branching 4: empty cells are unused slots wherever they fall
// among their siblings (slots 2, 5, 7, 18, 19), an unused cell's block is all unused, a used
// cell may have no children, and the options and evaluation follow the tree.
const std::string kOctreeShape =
    std::string(
        "3 4\n"
        "0.000000 0.000000 0.000000 1.732051 1.000000\n"
        "-0.500000 -0.500000 -0.500000 0.866025 1.000000\n") +
    unused_slots(1) +
    std::string(
        "0.500000 0.500000 -0.500000 0.866025 1.000000\n"
        "0.500000 0.500000 0.500000 0.866025 1.000000\n") +
    unused_slots(1) + std::string("-0.750000 -0.750000 -0.750000 0.433013 1.000000\n") +
    unused_slots(1) + std::string("-0.250000 -0.250000 -0.750000 0.433013 1.000000\n") +
    unused_slots(8) + std::string("0.750000 0.750000 0.750000 0.433013 1.000000\n") +
    unused_slots(2) +
    std::string(
        "0.250000 0.750000 0.750000 0.433013 1.000000\n"
        "\n"
        "Options : \n"
        "    Algorithm : Octree\n"
        "    Depth : 2\n"
        "\n"
        "Evaluation : \n"
        "    Level 1 : 3 spheres, worst error 0.366\n");

TEST(ToolkitFiles, OctreeShapeWithUnusedSlotsBetweenUsedOnes) {
  // The used slots in file order: 0; 1, 3, 4; 6, 8 (under slot 1); 17, 20 (under slot 4).
  const SphereTree tree = tree_of(kOctreeShape);
  expect_shape(tree, 4, 3, {-1, 0, 0, 0, 1, 1, 3, 3});
  EXPECT_EQ(tree.sphere(2).center, Vec3(0.5f, 0.5f, -0.5f));
  EXPECT_EQ(tree.sphere(5).center, Vec3(-0.25f, -0.25f, -0.75f));
  EXPECT_EQ(tree.sphere(7).center, Vec3(0.25f, 0.75f, 0.75f));
  EXPECT_EQ(tree.sphere(7).radius, 0.433013f);
  EXPECT_TRUE(tree.is_leaf(2));  // slot 3: its block is all unused
  EXPECT_EQ(tree.child_count(1), 2u);
}

// A medial-axis output (Hubbard, Merge, Burst, Expand, Combined) of 4 levels with branching 2:
// used lines carry the auxiliary sphere and its error (ten fields), unused slots the toolkit's
// -0.000001 or -1 with whatever centre was left in memory, first in their block as often as not.
const std::string kMedialShape =
    std::string(
        "4 2\n"
        "0.000000 0.000000 0.000000 2.000000 1.000000 0.000000 0.000000 0.000000 2.100000 "
        "0.100000\n"
        "-431602080.000000 -431602080.000000 -431602080.000000 -0.000001 0.000000\n"
        "1.000000 0.000000 0.000000 1.000000 0.500000 1.000000 0.000000 0.000000 1.100000 "
        "0.050000\n") +
    unused_slots(2) +
    std::string(
        "nan nan nan -1.000000 1.000000\n"
        "1.500000 0.000000 0.000000 0.500000 1.000000 1.500000 0.000000 0.000000 0.550000 "
        "0.020000\n") +
    unused_slots(6) +
    std::string(
        "1e20 -1e20 0.000000 -0.000001 0.000000\n"
        "1.750000 0.000000 0.000000 0.250000 1.000000\n"
        "Options : \n"
        "    Algorithm : Combined\n"
        "Evaluation : \n"
        "    Level 3 : 1 sphere\n");

TEST(ToolkitFiles, MedialShapeOfFourLevelsWithAuxiliarySpheres) {
  const SphereTree tree = tree_of(kMedialShape);
  expect_shape(tree, 2, 4, {-1, 0, 1, 2});
  EXPECT_EQ(tree.sphere(1).center, Vec3(1, 0, 0));
  EXPECT_EQ(tree.sphere(1).radius, 1.0f);
  EXPECT_EQ(tree.sphere(2).center, Vec3(1.5f, 0, 0));
  EXPECT_EQ(tree.sphere(3).center, Vec3(1.75f, 0, 0));
  EXPECT_EQ(tree.sphere(3).radius, 0.25f);
}

TEST(ToolkitFiles, CompactedTreesRoundTripUnchanged) {
  // Read, written (used children first, no gaps), read again: the same tree, and writing it
  // again gives the same text.
  for (const std::string& text : {kOctreeShape, kMedialShape}) {
    const SphereTree tree = tree_of(text);
    const std::string once = written(tree);
    EXPECT_EQ(tree_of(once), tree);
    EXPECT_EQ(written(tree_of(once)), once);
  }
}

TEST(ToolkitFiles, LevelsOfTheSpheresAsRead) {
  EXPECT_THAT(level_sizes(spheres_of(kOctreeShape)), ElementsAre(1u, 3u, 4u));
  EXPECT_THAT(level_sizes(spheres_of(kMedialShape)), ElementsAre(1u, 1u, 1u, 1u));
  EXPECT_EQ(spheres_of(kOctreeShape).nodes.size(), tree_of(kOctreeShape).size());
}

// A sphere set as the toolkit's saveSpheres writes it: the header "2 N", a bounding sphere, then
// the N spheres with four fields each.
std::string sphere_set(int count) {
  std::string text = "2 " + std::to_string(count) + "\n0.000000 0.000000 0.000000 3.000000\n";
  for (int i = 0; i < count; ++i) {
    text += std::to_string(0.1 * i) + " 0.000000 " + std::to_string(-0.05 * i) + " 0.250000\n";
  }
  return text;
}

TEST(ToolkitFiles, FlatSphereSetsOfMoreThanEight) {
  for (const int count : {12, 64}) {
    const SphSpheres set = spheres_of(sphere_set(count));
    EXPECT_EQ(set.branching, count);
    EXPECT_THAT(level_sizes(set), ElementsAre(1u, static_cast<std::size_t>(count)));
    const std::vector<std::vector<Sphere>> levels = set.levels();
    EXPECT_EQ(levels[1].back().center, Vec3(static_cast<float>(0.1 * (count - 1)), 0.0f,
                                            static_cast<float>(-0.05 * (count - 1))));
    EXPECT_EQ(levels[1].back().radius, 0.25f);
    for (const SphereTreeNode& node : set.nodes) EXPECT_LE(node.parent, 0);
  }
}

TEST(ToolkitFiles, ASphereSetIsNoSphereTreeForTheSimulation) {
  try {
    (void)tree_of(sphere_set(64));
    ADD_FAILURE() << "a branching factor of 64 read as a sphere-tree";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("toolkit.sph:1: branching factor 64 is above 8"));
  }
}

}  // namespace sphys::tools::toolkit_files_test
