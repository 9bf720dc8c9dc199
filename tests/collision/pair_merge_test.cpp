// merge_touched_pairs: a sorted pair list brought up to date from its touched keys, in runs of
// old pairs on threads, against the same lists made with the standard library's set algorithms.

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "collision/broad_phase.h"
#include "sphys/parallel.h"

namespace sphys {
namespace {

// Old pairs (several runs' worth), touched keys among and between them, some of which the table
// holds: the merge's new list, entered and left (after what they held) on no threads, one and
// four, against std::set_difference and std::set_union.
TEST(PairMerge, ManyRunsOnThreadsGiveTheSetAlgorithmsLists) {
  std::mt19937 random(2008);
  std::uniform_int_distribution<ProxyId> proxy(0, 400);
  std::set<std::uint64_t> old_keys;
  while (old_keys.size() < 9000) {
    const ProxyId a = proxy(random);
    const ProxyId b = proxy(random);
    if (a != b) old_keys.insert(pair_key(a, b));
  }
  // Touched: a third of the old keys and as many new ones; the table holds about half of them.
  std::set<std::uint64_t> touched;
  PairCounts table;
  for (const std::uint64_t key : old_keys) {
    if (random() % 3 == 0) touched.insert(key);
  }
  while (touched.size() < 6000) {
    const ProxyId a = proxy(random);
    const ProxyId b = proxy(random);
    if (a != b) touched.insert(pair_key(a, b));
  }
  for (const std::uint64_t key : touched) {
    if (random() % 2 == 0) table.insert(key);
  }
  std::set<std::uint64_t> expected;
  for (const std::uint64_t key : old_keys) {
    if (!touched.contains(key)) expected.insert(key);
  }
  for (const std::uint64_t key : touched) {
    if (table.contains(key)) expected.insert(key);
  }
  const auto pairs_of = [](const auto& keys) {
    std::vector<ProxyPair> pairs;
    for (const std::uint64_t key : keys) pairs.push_back(pair_of(key));
    return pairs;
  };
  std::vector<std::uint64_t> came;
  std::vector<std::uint64_t> went;
  std::set_difference(expected.begin(), expected.end(), old_keys.begin(), old_keys.end(),
                      std::back_inserter(came));
  std::set_difference(old_keys.begin(), old_keys.end(), expected.begin(), expected.end(),
                      std::back_inserter(went));
  const ProxyPair before{7, 8};  // a list's own entry, which the merge appends after

  const Parallel one(1);
  const Parallel four(4);
  for (const Parallel* parallel : {static_cast<const Parallel*>(nullptr), &one, &four}) {
    SCOPED_TRACE(parallel == nullptr ? 0 : parallel->threads());
    std::vector<ProxyPair> pairs = pairs_of(old_keys);
    const std::vector<std::uint64_t> touched_keys(touched.begin(), touched.end());
    PairMerge work;
    std::vector<ProxyPair> entered{before};
    std::vector<ProxyPair> left{before};
    merge_touched_pairs(pairs, touched_keys, table, work, entered, left, parallel);
    EXPECT_EQ(pairs, pairs_of(expected));
    std::vector<ProxyPair> expected_entered{before};
    std::vector<ProxyPair> expected_left{before};
    for (const ProxyPair& pair : pairs_of(came)) expected_entered.push_back(pair);
    for (const ProxyPair& pair : pairs_of(went)) expected_left.push_back(pair);
    EXPECT_EQ(entered, expected_entered);
    EXPECT_EQ(left, expected_left);
  }
}

}  // namespace
}  // namespace sphys
