#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/experiment.h"

namespace sphys::tools {
namespace {

// A frame's figures: `at_rest` of `moving` bodies at rest.
StepStats frame(std::uint32_t moving, std::uint32_t at_rest) {
  StepStats stats;
  stats.movable_bodies = moving;
  stats.bodies_at_rest = at_rest;
  return stats;
}

Plausibility measured(const std::vector<StepStats>& frames) {
  PlausibilityMeter meter;
  for (const StepStats& stats : frames) meter.add(stats);
  return meter.result();
}

TEST(PlausibilityMeter, NoFramesGiveNothing) {
  const Plausibility none = measured({});
  EXPECT_EQ(none.deepest_penetration, 0.0f);
  EXPECT_EQ(none.deepest_frame, 0);
  EXPECT_EQ(none.mean_penetration, 0.0);
  EXPECT_EQ(none.penetrating_frames, 0);
  EXPECT_FALSE(none.all_at_rest_frame.has_value());
  EXPECT_EQ(none.jitter, 0.0);
}

TEST(PlausibilityMeter, KeepsTheDeepestOverlapAndItsFrame) {
  std::vector<StepStats> frames(4, frame(2, 0));
  frames[1].deepest_penetration = 0.02f;
  frames[2].deepest_penetration = 0.05f;
  frames[3].deepest_penetration = 0.05f;  // as deep, later: the first frame stays
  const Plausibility figures = measured(frames);
  EXPECT_EQ(figures.deepest_penetration, 0.05f);
  EXPECT_EQ(figures.deepest_frame, 3);
}

TEST(PlausibilityMeter, MeanPenetrationLeavesOutFramesWithoutOverlaps) {
  std::vector<StepStats> frames(5, frame(1, 0));
  frames[1].penetrating_contacts = 3;
  frames[1].mean_penetration = 0.01;
  frames[3].penetrating_contacts = 1;
  frames[3].mean_penetration = 0.03;
  const Plausibility figures = measured(frames);
  EXPECT_DOUBLE_EQ(figures.mean_penetration, 0.02);
  EXPECT_EQ(figures.penetrating_frames, 2);
}

TEST(PlausibilityMeter, AllAtRestCountsFromTheLastTimeSomethingMoved) {
  // At rest in frames 2 and 3, moving again in 4, at rest from 5 to the end.
  const Plausibility settled =
      measured({frame(3, 1), frame(3, 3), frame(3, 3), frame(3, 2), frame(3, 3), frame(3, 3)});
  ASSERT_TRUE(settled.all_at_rest_frame.has_value());
  EXPECT_EQ(*settled.all_at_rest_frame, 5);
  // Moving in the last frame: never all at rest for good.
  EXPECT_FALSE(measured({frame(3, 3), frame(3, 2)}).all_at_rest_frame.has_value());
  // Nothing that moves is at rest from the first frame.
  EXPECT_EQ(measured({frame(0, 0), frame(0, 0)}).all_at_rest_frame, 1);
}

TEST(PlausibilityMeter, TheEndStateIsTheLastFrames) {
  StepStats last = frame(4, 3);
  last.bodies_asleep = 2;
  last.kinetic_energy = 1.5;
  StepStats first = frame(5, 0);
  first.kinetic_energy = 99.0;
  const Plausibility figures = measured({first, last});
  EXPECT_EQ(figures.movable_bodies, 4u);
  EXPECT_EQ(figures.bodies_at_rest, 3u);
  EXPECT_EQ(figures.bodies_asleep, 2u);
  EXPECT_EQ(figures.final_kinetic_energy, 1.5);
}

TEST(PlausibilityMeter, JitterIsTheMeanOverTheLastFrames) {
  // Fewer frames than kJitterFrames: all of them.
  std::vector<StepStats> few(3, frame(1, 1));
  few[0].jitter = 0.3;
  few[1].jitter = 0.6;
  EXPECT_DOUBLE_EQ(measured(few).jitter, 0.3);

  // More: only the last kJitterFrames count, the settling before them does not.
  std::vector<StepStats> many(kJitterFrames + 25, frame(1, 1));
  for (std::size_t i = 0; i < 25; ++i) many[i].jitter = 100.0;
  for (std::size_t i = 25; i < many.size(); ++i) many[i].jitter = 0.25;
  EXPECT_DOUBLE_EQ(measured(many).jitter, 0.25);
}

}  // namespace
}  // namespace sphys::tools
