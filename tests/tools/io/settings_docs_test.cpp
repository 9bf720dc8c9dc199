#include "sphys/tools/settings_docs.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/tools/scene_file.h"
#include "sphys/world.h"
#include "support/setting_edges.h"

namespace sphys {
namespace {

using test::Edge;
using test::edges;
using test::has_range;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// A scene with `value` under `key` in the setting's object, and nothing else but what a scene
// needs.
std::string scene_with(const Setting& setting, std::string_view key, const nlohmann::json& value) {
  nlohmann::json scene = {
      {"format", "sphys-scene"}, {"version", 1}, {"bodies", nlohmann::json::array()}};
  nlohmann::json& object = setting.object.empty() ? scene : scene[std::string(setting.object)];
  object[std::string(key)] = value;
  return scene.dump();
}

std::string pointer_of(const Setting& setting) {
  return (setting.object.empty() ? "" : "/" + std::string(setting.object)) + "/" +
         std::string(setting.key);
}

// The figure as a scene file writes it: a count as an integer.
nlohmann::json figure(const Setting& setting, double value) {
  if (setting.kind == SettingKind::kInteger) return static_cast<std::int64_t>(value);
  return value;
}

TEST(SceneSettings, TheReaderTakesEveryBoundAndRefusesWhatLiesBeyond) {
  const std::string path = "scene.json";
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene) continue;
    SCOPED_TRACE(setting.field);
    const auto read = [&](const nlohmann::json& value) {
      return tools::world_settings(
          tools::parse_scene(scene_with(setting, setting.key, value), path));
    };
    const auto refused = [&](const nlohmann::json& value) {
      SCOPED_TRACE(value.dump());
      try {
        (void)read(value);
        ADD_FAILURE() << "accepted";
      } catch (const Error& error) {
        // The setting's pointer, or one of a vector's components.
        EXPECT_THAT(error.what(), StartsWith(path + ": " + pointer_of(setting)));
      }
    };
    switch (setting.kind) {
      case SettingKind::kInteger:
      case SettingKind::kNumber:
        for (const Edge& edge : edges(setting)) {
          SCOPED_TRACE(edge.at);
          // Compared as floats: the reader keeps a float figure as its shortest decimal form.
          EXPECT_EQ(static_cast<float>(setting.get(read(figure(setting, edge.at)))),
                    static_cast<float>(edge.at));
          refused(figure(setting, edge.beyond));
        }
        if (setting.kind == SettingKind::kInteger && !(setting.range.min > 0.0)) {
          refused(-1);  // below a count's 0, which the runtime cannot even hold
        }
        refused("1");
        break;
      case SettingKind::kEnum:
        for (std::size_t i = 0; i < setting.choices.size(); ++i) {
          EXPECT_EQ(setting.get(read(std::string(setting.choices[i]))), static_cast<double>(i));
        }
        refused("no-such-choice");
        break;
      case SettingKind::kBool:
        EXPECT_EQ(setting.get(read(false)), 0.0);
        EXPECT_EQ(setting.get(read(true)), 1.0);
        refused(1);
        break;
      case SettingKind::kVector3:
        EXPECT_EQ(setting.get_vector(read({1.5, -2.0, 3.0})), Vec3(1.5f, -2.0f, 3.0f));
        refused({0.0, 1.0});
        refused({0.0, 1e39, 0.0});
        break;
    }
  }
}

TEST(SceneSettings, TheReaderSuggestsTheSettingAMisspeltKeyMeant) {
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene) continue;
    std::string misspelt(setting.key);
    misspelt.pop_back();
    try {
      (void)tools::parse_scene(scene_with(setting, misspelt, 1), "scene.json");
      ADD_FAILURE() << misspelt << " accepted";
    } catch (const Error& error) {
      EXPECT_THAT(error.what(),
                  HasSubstr("unknown key; did you mean \"" + std::string(setting.key) + "\"?"));
    }
  }
}

std::filesystem::path docs_folder() {
  return std::filesystem::path(__FILE__).parent_path() / "../../../docs";
}

std::string docs_text(std::string_view name) {
  const std::filesystem::path path = docs_folder() / name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot open " << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Compares a committed document with what the table makes of it; with SPHYS_UPDATE_DOCS=1 in the
// environment, writes the table's version instead.
void expect_made_from_table(std::string_view name, const std::string& committed,
                            const std::string& made) {
  const char* update = std::getenv("SPHYS_UPDATE_DOCS");
  if (update != nullptr && std::string_view(update) == "1" && made != committed) {
    std::ofstream(docs_folder() / name, std::ios::binary) << made;
    return;
  }
  EXPECT_EQ(made, committed) << "docs/" << name
                             << " differs from the settings table; run this test with "
                                "SPHYS_UPDATE_DOCS=1 to rewrite it";
}

TEST(SettingsDocs, TheSchemaIsMadeFromTheTable) {
  const std::string committed = docs_text("scene.schema.json");
  expect_made_from_table("scene.schema.json", committed,
                         tools::scene_schema_with_settings(committed));
}

TEST(SettingsDocs, TheScenesPageIsMadeFromTheTable) {
  const std::string committed = docs_text("scenes.md");
  expect_made_from_table("scenes.md", committed, tools::scenes_doc_with_settings(committed));
}

TEST(SettingsDocs, TheSchemaSaysWhatTheReaderTakes) {
  // Each scene setting's bounds in the committed schema are the table's, by the same names.
  const nlohmann::json schema = nlohmann::json::parse(docs_text("scene.schema.json"));
  for (const Setting& setting : settings_table()) {
    if (!setting.in_scene) continue;
    SCOPED_TRACE(setting.field);
    const nlohmann::json& property = setting.object.empty()
                                         ? schema.at("properties").at(std::string(setting.key))
                                         : schema.at("$defs")
                                               .at(std::string(setting.object))
                                               .at("properties")
                                               .at(std::string(setting.key));
    if (!has_range(setting)) continue;
    const SettingRange& range = setting.range;
    EXPECT_EQ(property.at(range.min_inclusive ? "minimum" : "exclusiveMinimum").get<double>(),
              range.min);
    if (range.has_max()) {
      EXPECT_EQ(property.at("maximum").get<double>(), range.max);
    }
    EXPECT_EQ(property.contains("maximum") || property.contains("exclusiveMaximum"),
              range.has_max());
  }
}

TEST(SettingsDocs, MakingTheDocsNeedsTheirSections) {
  EXPECT_THROW((void)tools::scenes_doc_with_settings("# Scene files\n"), Error);
  EXPECT_THROW((void)tools::scene_schema_with_settings("{}"), Error);
  EXPECT_THROW((void)tools::scene_schema_with_settings("not json"), Error);
}

}  // namespace
}  // namespace sphys
