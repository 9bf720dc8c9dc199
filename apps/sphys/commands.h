#pragma once

#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/tools/setting_text.h"

namespace sphys::cli {

// The value of a named option read by `parse` (e.g. tools::parse_response_mode); its
// sphys::Error gains the option's name, so the message says which option was wrong.
template <typename Parse>
auto parse_option(std::string_view option, std::string_view value, Parse parse) {
  try {
    return parse(value);
  } catch (const Error& error) {
    std::string message(option);
    message += ": ";
    message += error.what();
    throw Error(message);
  }
}

// For options and arguments naming a file or folder: an empty name is refused by the option's
// name ("--output: expected a file name, got \"\"") rather than failing later on a file called "".
inline const CLI::Validator kFileName(
    [](const std::string& value) {
      return value.empty() ? std::string("expected a file name, got \"\"") : std::string();
    },
    "");

// An integer option's value, which must lie in the range of the setting it sets; else
// sphys::Error "<option> must be between 1 and 64, got 0".
inline int checked_count(std::string_view option, int value, const Setting& setting) {
  if (!setting.range.contains(value)) {
    std::string message(option);
    message += " must be between " + number_text(setting.range.min) + " and " +
               number_text(setting.range.max) + ", got " + std::to_string(value);
    throw Error(message);
  }
  return value;
}

// The --help text of an option that sets a world setting: its documentation, valid values and
// unit, from the settings table.
inline std::string setting_help(std::string_view field) { return option_help(setting_of(field)); }

// Each subcommand lives in its own file and registers itself on the top-level app. Its callback
// throws sphys::Error for bad input (exit code 2) and anything else for internal errors (1).
void add_mesh_info_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_build_tree_command(CLI::App& app);
void add_tree_info_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_experiment_command(CLI::App& app);
void add_spherize_command(CLI::App& app);
void add_cache_command(CLI::App& app);
void add_query_command(CLI::App& app);

}  // namespace sphys::cli
