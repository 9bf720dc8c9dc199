#pragma once

// What a ConfigurationChecker works in, one per run of configurations and per Run: each link's box
// around its spheres (link_boxes.cpp) and the groups near it (near_groups.cpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "query/snapshot.h"
#include "sphys/configuration_check.h"

namespace sphys {

// Per link of one configuration (or of several gathered: Run::gather), the box around its
// spheres, and the groups near it.
struct ConfigurationChecker::Scratch {
  // Groups kept per link; a link near more is checked sphere by sphere through the hierarchy.
  static constexpr std::uint32_t kMostCandidates = 32;
  static constexpr std::int32_t kTooMany = -2;

  Scratch(std::span<const std::int32_t> links, std::size_t link_count)
      : row_length((link_count + query_detail::kLaneWidth - 1) / query_detail::kLaneWidth *
                   query_detail::kLaneWidth),
        box(6 * row_length, 0.0f),
        spheres(link_count),
        candidates(link_count * kMostCandidates),
        candidate_count(link_count) {
    for (const std::int32_t link : links) ++spheres[static_cast<std::size_t>(link)];
  }

  // Row r of the links' boxes (0..2 low x, y, z, 3..5 high x, y, z), a link a column.
  float* row(std::size_t r) { return box.data() + r * row_length; }
  const float* row(std::size_t r) const { return box.data() + r * row_length; }

  // Every link's box empty, for the min and max of what it holds.
  void empty_links() {
    for (std::size_t a = 0; a < 3; ++a) {
      std::fill_n(row(a), spheres.size(), std::numeric_limits<float>::infinity());
      std::fill_n(row(3 + a), spheres.size(), -std::numeric_limits<float>::infinity());
    }
  }

  // Link l's box grown to hold the box [low, high] (x, y, z each).
  void hold(std::size_t l, const float* low, const float* high) {
    for (std::size_t a = 0; a < 3; ++a) {
      row(a)[l] = std::min(row(a)[l], low[a]);
      row(3 + a)[l] = std::max(row(3 + a)[l], high[a]);
    }
  }

  // Each link's box: around its spheres, a run of one link's spheres bounded in registers
  // before its box holds them.
  void bound_links(const float* posed, std::span<const std::int32_t> links);

  // For configurations gathered together: each sphere's (x, y, z, radius) least and greatest
  // over all of them, for every sphere or (near_links_only) those of links near a group alone.
  // Whether each of those spheres is finite.
  bool bound_spheres(const float* posed, std::size_t configurations,
                     std::span<const std::int32_t> links, bool near_links_only);

  // Each link's box around its spheres' boxes (bound_spheres, every sphere) grown by their
  // radii.
  void box_links_from_spheres(std::span<const std::int32_t> links);

  // Rounding c ± r to float may leave a sphere's surface up to half an ulp outside its link's
  // box: each box is widened by a millionth of its size and distance from the origin, far more
  // than that. A link without spheres keeps its empty box (infinities, which the margin would
  // turn into NaN).
  void widen_links();

  // Whole lanes: collect_candidates loads the rows a register at a time. unit: links
  std::size_t row_length;
  // Each link's box: rows low x, y, z, high x, y, z (row()), a link a column. unit: m
  query_detail::LaneFloats box;
  std::vector<std::uint32_t> spheres;  // each link's count
  std::vector<std::uint32_t> candidates;
  std::vector<std::int32_t> candidate_count;
  // Gathered configurations: each sphere's (x, y, z, radius) least and greatest over them, and
  // the spheres whose bound touches a leaf, in order, once known.
  query_detail::LaneFloats least;
  query_detail::LaneFloats greatest;
  std::vector<std::uint32_t> bounded;  // the spheres bound_spheres bounded
  std::vector<std::uint32_t> near;
  bool near_known = false;
  // The box around every link's, where the caller bounded the links (Run::bound): a group
  // outside it meets none of them. unit: m
  Aabb around;
  bool around_known = false;
};

}  // namespace sphys
