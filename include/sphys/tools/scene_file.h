#pragma once

// JSON scene files, format "sphys-scene" version 1: docs/scenes.md describes every key,
// docs/scene.schema.json is its JSON Schema.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/tools/recording.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {

// Reads a scene file. The scene's name is the file's name and its base_directory the file's
// folder, against which relative mesh and .sph paths resolve; those files must exist (the default
// model "bunny" excepted). Throws sphys::Error naming the file and, for a bad value, its JSON
// pointer ("/bodies/3/density") with the reason; for text that is not JSON, its line and column.
[[nodiscard]] Scene read_scene_file(const std::filesystem::path& path);

// The same for text, as if read from a file at `name` (used in messages, for Scene::name and for
// the base directory).
[[nodiscard]] Scene parse_scene(std::string_view json_text, const std::filesystem::path& name);

// The scene a recording embeds (Recording::metadata), as parse_scene reads it, less the settings
// sphys no longer has (removed_setting): recordings made before they were removed carry them.
[[nodiscard]] Scene parse_recorded_scene(std::string_view json_text,
                                         const std::filesystem::path& name);

// The scene as pretty JSON (2-space indent) with every key written out, ready to be embedded in a
// recording. parse_scene reads it back to an equal scene, every number bit for bit, when the
// scene is one parse_scene accepts. Neither the name nor the base directory is written: mesh and
// .sph paths stay as given, relative to base_directory. A tree read from a .sph file is written
// as its path alone, so its build settings are not kept.
[[nodiscard]] std::string scene_to_json(const Scene& scene);

// The scene as a recording embeds it: scene_to_json with every file path (meshes, .sph files,
// robots' files and package folders) made absolute, so that a viewer replaying the recording from
// any folder finds them.
[[nodiscard]] std::string recorded_scene_json(Scene scene);

// The scene's joints as a recording keeps them (RecordingWriter), in the scene's order.
[[nodiscard]] std::vector<RecordedJoint> recorded_joints(const Scene& scene);

}  // namespace sphys::tools
