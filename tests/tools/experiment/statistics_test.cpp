#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sphys/tools/experiment.h"
#include "sphys/tools/median.h"

namespace sphys::tools {
namespace {

RowSummary summary(double contacts, double fps, double frame_sd, double detection,
                   double response) {
  RowSummary row;
  row.contacts_per_frame = contacts;
  row.fps = fps;
  row.frame_time_sd_ms = frame_sd;
  row.detection_share = detection;
  row.response_share = response;
  return row;
}

TEST(Quantile, GivesTheValueAtTheNearestRank) {
  const std::vector<double> values = {5, 1, 4, 2, 3, 9, 7, 6, 8, 10, 0};  // 0 to 10, shuffled
  EXPECT_EQ(quantile(values, 0.0), 0.0);
  EXPECT_EQ(quantile(values, 1.0), 10.0);
  EXPECT_EQ(quantile(values, 0.9), 9.0);
  EXPECT_EQ(quantile(values, 0.5), median(values));
  EXPECT_EQ(quantile(values, 0.34), 3.0);  // rank 3.4
  EXPECT_EQ(quantile(values, 0.36), 4.0);  // rank 3.6
  EXPECT_EQ(quantile({}, 0.9), 0.0);
}

TEST(ExperimentPearson, PerfectlyCorrelatedSequencesGivePlusOrMinusOne) {
  const std::vector<double> x = {1, 2, 3, 4};
  EXPECT_DOUBLE_EQ(pearson(x, std::vector<double>{2, 4, 6, 8}), 1.0);
  EXPECT_DOUBLE_EQ(pearson(x, std::vector<double>{-1, -3, -5, -7}), -1.0);
}

TEST(ExperimentPearson, MatchesHandComputedCoefficients) {
  // Deviations (-2 -1 0 1 2) and (-1 -2 1 0 2): sxy = 8, sxx = syy = 10, r = 0.8.
  EXPECT_NEAR(pearson(std::vector<double>{1, 2, 3, 4, 5}, std::vector<double>{2, 1, 4, 3, 5}), 0.8,
              1e-15);
  // Deviations (-1 0 1) and (-1 1 0): sxy = 1, sxx = syy = 2, r = 0.5.
  EXPECT_NEAR(pearson(std::vector<double>{1, 2, 3}, std::vector<double>{1, 3, 2}), 0.5, 1e-15);
}

TEST(ExperimentPearson, KeepsPrecisionFarFromTheOrigin) {
  // The same r = 0.5 as above, shifted by 1e12: sums of squares of the values (1e24) would
  // swallow the deviations entirely.
  EXPECT_NEAR(
      pearson(std::vector<double>{1e12 + 1, 1e12 + 2, 1e12 + 3}, std::vector<double>{1, 3, 2}), 0.5,
      1e-12);
}

TEST(ExperimentPearson, IsNaNWithoutTwoPairsOrWithoutSpread) {
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{}, std::vector<double>{})));
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{1}, std::vector<double>{2})));
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{1, 2, 3}, std::vector<double>{1, 2})));
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{2, 2, 2}, std::vector<double>{1, 2, 3})));
  EXPECT_TRUE(
      std::isnan(pearson(std::vector<double>{1, 2, 3}, std::vector<double>{0.1, 0.1, 0.1})));
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{1, NAN, 3}, std::vector<double>{1, 2, 3})));
}

TEST(ExperimentSummary, MatchesHandComputedFigures) {
  RowResult result;
  result.row = {3, 8, 20};
  result.frames = {{2.0, 0.5, 1.0, 10}, {4.0, 1.0, 1.5, 20}, {6.0, 1.5, 2.5, 30}};
  const RowSummary s = summarize(result);
  EXPECT_EQ(s.row, (ExperimentRow{3, 8, 20}));
  EXPECT_DOUBLE_EQ(s.contacts_per_frame, 20.0);
  EXPECT_DOUBLE_EQ(s.mean_frame_ms, 4.0);
  EXPECT_DOUBLE_EQ(s.fps, 250.0);
  // Deviations -2 0 2: (4 + 0 + 4) / (3 - 1) = 4; the population sd would be sqrt(8/3).
  EXPECT_DOUBLE_EQ(s.frame_time_sd_ms, 2.0);
  EXPECT_DOUBLE_EQ(s.detection_share, 100.0 * 3.0 / 12.0);
  EXPECT_DOUBLE_EQ(s.response_share, 100.0 * 5.0 / 12.0);
}

TEST(ExperimentSummary, FrameTimeSdKeepsPrecisionFarFromTheOrigin) {
  RowResult result;
  for (const double ms : {1e9 + 1, 1e9 + 2, 1e9 + 3}) result.frames.push_back({ms, 0.0, 0.0, 0});
  EXPECT_DOUBLE_EQ(summarize(result).frame_time_sd_ms, 1.0);
}

TEST(ExperimentSummary, FiguresARunCannotGiveAreNaN) {
  const RowSummary none = summarize(RowResult{});
  EXPECT_TRUE(std::isnan(none.contacts_per_frame));
  EXPECT_TRUE(std::isnan(none.mean_frame_ms));
  EXPECT_TRUE(std::isnan(none.fps));
  EXPECT_TRUE(std::isnan(none.frame_time_sd_ms));
  EXPECT_TRUE(std::isnan(none.detection_share));
  EXPECT_TRUE(std::isnan(none.response_share));

  RowResult one;
  one.frames = {{8.0, 2.0, 4.0, 7}};
  const RowSummary single = summarize(one);
  EXPECT_DOUBLE_EQ(single.fps, 125.0);
  EXPECT_DOUBLE_EQ(single.detection_share, 25.0);
  EXPECT_DOUBLE_EQ(single.response_share, 50.0);
  EXPECT_TRUE(std::isnan(single.frame_time_sd_ms));

  RowResult untimed;
  untimed.frames = {{0.0, 0.0, 0.0, 3}, {0.0, 0.0, 0.0, 5}};
  const RowSummary zero = summarize(untimed);
  EXPECT_DOUBLE_EQ(zero.contacts_per_frame, 4.0);
  EXPECT_TRUE(std::isnan(zero.fps));
  EXPECT_TRUE(std::isnan(zero.detection_share));
}

TEST(ExperimentStatistics, MatchesHandComputedFiguresForThreeRows) {
  // Contacts deviate by -100, 0, 100 (sxx = 20000).
  const std::vector<RowSummary> rows = {
      summary(100, 60, 1, 20, 30),
      summary(200, 30, 2, 22, 40),
      summary(300, 30, 4, 30, 35),
  };
  const ExperimentStatistics s = compute_statistics(rows);
  // FPS deviations 20 -10 -10: sxy = -3000, syy = 600, r = -3000 / sqrt(12e6) = -sqrt(3)/2.
  EXPECT_NEAR(s.contacts_fps_correlation, -std::sqrt(3.0) / 2.0, 1e-14);
  // sd deviations -4/3 -1/3 5/3: sxy = 300, syy = 14/3, r = sqrt(27/28).
  EXPECT_NEAR(s.contacts_frame_sd_correlation, std::sqrt(27.0 / 28.0), 1e-14);
  // Detection shares 20 22 30: mean 24, deviations -4 -2 6, sample variance 56 / 2 = 28;
  // sxy = 1000, syy = 56, r = sqrt(25/28).
  EXPECT_DOUBLE_EQ(s.detection_share_mean, 24.0);
  EXPECT_NEAR(s.detection_share_sd, std::sqrt(28.0), 1e-14);
  EXPECT_NEAR(s.detection_share_contacts_correlation, std::sqrt(25.0 / 28.0), 1e-14);
  // Response shares 30 40 35: mean 35, deviations -5 5 0, sample variance 50 / 2 = 25;
  // sxy = 500, syy = 50, r = 500 / 1000.
  EXPECT_DOUBLE_EQ(s.response_share_mean, 35.0);
  EXPECT_DOUBLE_EQ(s.response_share_sd, 5.0);
  EXPECT_NEAR(s.response_share_contacts_correlation, 0.5, 1e-14);
}

TEST(ExperimentStatistics, OneRowGivesMeansButNoSpreadOrCorrelation) {
  const std::vector<RowSummary> rows = {summary(100, 60, 1, 20, 30)};
  const ExperimentStatistics s = compute_statistics(rows);
  EXPECT_DOUBLE_EQ(s.detection_share_mean, 20.0);
  EXPECT_DOUBLE_EQ(s.response_share_mean, 30.0);
  EXPECT_TRUE(std::isnan(s.detection_share_sd));
  EXPECT_TRUE(std::isnan(s.response_share_sd));
  EXPECT_TRUE(std::isnan(s.contacts_fps_correlation));
  EXPECT_TRUE(std::isnan(s.response_share_contacts_correlation));
}

TEST(ExperimentPaperTable, HoldsTable1InThePrintedOrder) {
  struct Expected {
    std::string id;
    double contacts;
    double fps;
    double frame_sd_ms;
  };
  const std::vector<Expected> expected = {
      {"d2-4x25", 4216.81, 57.47, 5.89},    {"d2-4x50", 5621.16, 33.29, 7.79},
      {"d3-4x25", 122445.31, 12.70, 35.96}, {"d3-4x50", 542613.84, 3.34, 302.89},
      {"d2-8x10", 16381.50, 43.80, 9.25},   {"d2-8x20", 12771.69, 31.50, 8.29},
      {"d3-8x10", 77246.49, 17.41, 18.92},  {"d3-8x20", 265562.60, 6.91, 69.29},
  };
  const auto table = paper_table();
  ASSERT_EQ(table.size(), expected.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    SCOPED_TRACE(expected[i].id);
    EXPECT_EQ(table[i].row.id(), expected[i].id);
    EXPECT_EQ(table[i].contacts_per_frame, expected[i].contacts);
    EXPECT_EQ(table[i].fps, expected[i].fps);
    EXPECT_EQ(table[i].frame_time_sd_ms, expected[i].frame_sd_ms);
  }
}

TEST(ExperimentPaperTable, IdsNameDepthStacksAndBunniesPerStack) {
  EXPECT_EQ((ExperimentRow{2, 4, 25}).id(), "d2-4x25");
  EXPECT_EQ((ExperimentRow{3, 8, 20}).id(), "d3-8x20");
  EXPECT_EQ((ExperimentRow{4, 12, 100}).id(), "d4-12x100");
}

TEST(ExperimentPaperTable, HoldsTheSection5StatisticsAsPrinted) {
  const ExperimentStatistics& s = paper_statistics();
  EXPECT_EQ(s.contacts_fps_correlation, 0.75);
  EXPECT_EQ(s.contacts_frame_sd_correlation, 0.96);
  EXPECT_EQ(s.detection_share_mean, 23.0);
  EXPECT_EQ(s.detection_share_sd, 0.08);
  EXPECT_EQ(s.response_share_mean, 40.0);
  EXPECT_EQ(s.response_share_sd, 0.26);
  EXPECT_EQ(s.detection_share_contacts_correlation, -0.59);
  EXPECT_EQ(s.response_share_contacts_correlation, 0.88);
}

TEST(ExperimentPaperTable, CorrelationsRecomputedFromTable1) {
  std::vector<double> contacts;
  std::vector<double> fps;
  std::vector<double> frame_sd;
  for (const PaperRow& row : paper_table()) {
    contacts.push_back(row.contacts_per_frame);
    fps.push_back(row.fps);
    frame_sd.push_back(row.frame_time_sd_ms);
  }
  // Reference values from an independent implementation (Python's statistics.correlation).
  // The paper prints +0.96 for the first and +0.75 for the second, although its text says FPS
  // falls as contacts rise.
  EXPECT_NEAR(pearson(contacts, frame_sd), 0.961187255801569, 1e-12);
  EXPECT_NEAR(pearson(contacts, fps), -0.754661261670202, 1e-12);
}

}  // namespace
}  // namespace sphys::tools
