#include "sphys/settings_table.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/world.h"
#include "support/setting_edges.h"

namespace sphys {
namespace {

using test::Edge;
using test::edges;
using test::has_range;
using ::testing::StartsWith;

TEST(SettingsTable, EveryFieldHasOneEntryWithADefaultInItsRange) {
  std::vector<std::string> places;
  for (const Setting& setting : settings_table()) {
    SCOPED_TRACE(setting.field);
    EXPECT_FALSE(setting.doc.empty());
    EXPECT_EQ(&setting_of(setting.field), &setting);
    if (setting.in_scene) {
      EXPECT_FALSE(setting.key.empty());
    }
    if (setting.kind == SettingKind::kEnum) {
      EXPECT_GE(setting.choices.size(), 2u);
    }
    if (has_range(setting)) {
      EXPECT_TRUE(setting.range.contains(setting.get(WorldSettings{})));
      EXPECT_TRUE(setting.range.has_min()) << "every count and figure has a lower bound";
    }
    if (setting.in_scene) {
      const std::string place = std::string(setting.object) + "/" + std::string(setting.key);
      EXPECT_EQ(std::count(places.begin(), places.end(), place), 0) << "two settings at " << place;
      places.push_back(place);
    }
  }
  EXPECT_NO_THROW(check_world_settings(WorldSettings{}));
  EXPECT_THROW((void)setting_of("solver.no_such_setting"), std::out_of_range);
}

TEST(SettingsTable, ValidationTakesEveryBoundAndRefusesWhatLiesBeyond) {
  for (const Setting& setting : settings_table()) {
    SCOPED_TRACE(setting.field);
    const auto refused = [&](const WorldSettings& settings) {
      try {
        check_world_settings(settings);
        ADD_FAILURE() << "accepted";
      } catch (const Error& error) {
        EXPECT_THAT(error.what(), StartsWith(std::string(setting.field) + " must be "));
      }
    };
    WorldSettings settings;
    switch (setting.kind) {
      case SettingKind::kInteger:
      case SettingKind::kNumber:
        for (const Edge& edge : edges(setting)) {
          SCOPED_TRACE(edge.at);
          setting.set(settings, edge.at);
          EXPECT_NO_THROW(check_world_settings(settings));
          setting.set(settings, edge.beyond);
          refused(settings);
        }
        if (setting.kind == SettingKind::kNumber) {
          setting.set(settings, std::numeric_limits<double>::quiet_NaN());
          refused(settings);
          setting.set(settings, std::numeric_limits<double>::infinity());
          refused(settings);
        }
        break;
      case SettingKind::kEnum:
        for (std::size_t i = 0; i < setting.choices.size(); ++i) {
          setting.set(settings, static_cast<double>(i));
          EXPECT_NO_THROW(check_world_settings(settings));
        }
        setting.set(settings, static_cast<double>(setting.choices.size()));
        refused(settings);
        break;
      case SettingKind::kVector3:
        // Every component is held to the range on its own.
        ASSERT_TRUE(setting.range.has_min() && setting.range.has_max());
        for (int k = 0; k < 3; ++k) {
          for (const Edge& edge : edges(setting)) {
            SCOPED_TRACE("component " + std::to_string(k) + " at " + std::to_string(edge.at));
            Vec3 value(1.0f, -2.0f, 3.0f);
            value[k] = static_cast<float>(edge.at);
            setting.set_vector(settings, value);
            EXPECT_NO_THROW(check_world_settings(settings));
            value[k] = static_cast<float>(edge.beyond);
            setting.set_vector(settings, value);
            refused(settings);
          }
          Vec3 value = Vec3::Zero();
          value[k] = std::numeric_limits<float>::infinity();
          setting.set_vector(settings, value);
          refused(settings);
          value[k] = std::numeric_limits<float>::quiet_NaN();
          setting.set_vector(settings, value);
          refused(settings);
        }
        break;
      case SettingKind::kBool:
        setting.set(settings, 0.0);
        EXPECT_NO_THROW(check_world_settings(settings));
        break;
    }
  }
}

TEST(SettingsTable, MessagesNameTheFieldTheRangeTheValueAndItsUnit) {
  const auto message = [](auto change) {
    WorldSettings settings;
    change(settings);
    try {
      check_world_settings(settings);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message([](WorldSettings& s) { s.solver.manifold_points = 9; }),
            "solver.manifold_points must be between 1 and 8, got 9 contacts");
  EXPECT_EQ(message([](WorldSettings& s) { s.sleep.speed = -0.5f; }),
            "sleep.speed must be finite and not negative, got -0.5 m/s");
  EXPECT_EQ(message([](WorldSettings& s) { s.collision_pass_travel = 0.0f; }),
            "collision_pass_travel must be positive and finite, got 0 bounding radii");
  EXPECT_EQ(message([](WorldSettings& s) { s.ground_restitution = 1.5f; }),
            "ground_restitution must be between 0 and 1, got 1.5");
  EXPECT_EQ(message([](WorldSettings& s) { s.gravity = Vec3(0.0f, -3e38f, 0.0f); }),
            "gravity must be between -1000 and 1000 in each component, got [0, -3e+38, 0] m/s²");
}

}  // namespace
}  // namespace sphys
