#pragma once

// The parts of the scene format's documents that describe the world's settings, made from the
// settings table (sphys/settings_table.h): the JSON Schema's properties and the rows of
// docs/scenes.md's tables. A test compares them with the committed files; setting
// SPHYS_UPDATE_DOCS=1 when running it writes them instead.

#include <string>
#include <string_view>

namespace sphys::tools {

// The schema (docs/scene.schema.json) with the properties of every scene setting made from the
// table: the top level's, "$defs/solver" and "$defs/sleep" whole, the ground's material. The rest
// is kept, laid out as the committed file is (objects one member a line, short lists and small
// objects of plain values on one line). Throws sphys::Error when the text is not such a schema.
[[nodiscard]] std::string scene_schema_with_settings(std::string_view schema);

// docs/scenes.md with the rows of every scene setting made from the table. In the sections "Top
// level", "Solver", "Sleep" and "Ground", the rows of an object's settings must follow one
// another, in any order; they are replaced by the table's, in its order. Throws sphys::Error when
// a section or its rows cannot be found, or another row lies among them.
[[nodiscard]] std::string scenes_doc_with_settings(std::string_view doc);

}  // namespace sphys::tools
