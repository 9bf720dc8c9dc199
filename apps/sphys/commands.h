#pragma once

#include <CLI/CLI.hpp>

namespace sphys::cli {

// Each subcommand lives in its own file and registers itself on the top-level app. Its callback
// throws sphys::Error for bad input (exit code 2) and anything else for internal errors (1).
void add_mesh_info_command(CLI::App& app);
void add_build_tree_command(CLI::App& app);
void add_tree_info_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_experiment_command(CLI::App& app);

}  // namespace sphys::cli
