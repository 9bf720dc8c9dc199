#pragma once

// The narrow phase's work on a run of jobs (candidate pairs, or bodies against the ground plane),
// done on one thread into its own buffers: its leaf spheres, its pairs, and their contacts and
// shapes, with the run's figures. The runs' contacts are placed in the jobs' order, so the result
// is the same whatever thread did which run.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "collision/collision_detector.h"
#include "collision/contact_reduction.h"
#include "collision/tree_descent.h"

namespace sphys {

struct CollisionDetector::NarrowChunk {
  std::size_t begin = 0;  // jobs
  std::size_t end = 0;
  TreeDescent descent;
  ContactReducer reducer;
  std::vector<NodePair> node_pairs;
  std::vector<std::uint32_t> plane_stack;
  std::vector<LeafSpheres> leaves;
  std::vector<PairLeaves> pairs;
  std::vector<Contact> run;          // one pair's leaf contacts, before reduction
  std::vector<std::uint64_t> parts;  // per contact of the run, its pair of parts (fast pairs)
  std::vector<Contact> contacts;
  std::vector<ContactShape> shapes;
  std::size_t base = 0;  // where its contacts start in the cache's
  std::uint32_t parted_pairs = 0;
  DetectionCounters counters;
  float deepest_penetration = 0.0f;
  double penetration_sum = 0.0;
  std::uint32_t penetrating_contacts = 0;
};

}  // namespace sphys
