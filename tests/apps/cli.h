#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/run_command.h"
#include "support/temp_file.h"

namespace sphys::test {

// The sphys program built with the tests (its path comes from CMake).
inline CommandResult sphys_cli(const std::vector<std::string>& args) {
  return run_command(SPHYS_CLI_PATH, args);
}

// The sphys program started by /bin/sh after `setup`: shell commands that put in a fault the way a
// user would (`ulimit -n 4`, `exec >/dev/full`, `trap '' XFSZ`), which reach sphys through exec.
inline CommandResult sphys_cli_after(const std::string& setup,
                                     const std::vector<std::string>& args) {
  std::vector<std::string> shell_args = {"-c", "set -e\n" + setup + "\nexec \"$0\" \"$@\"",
                                         SPHYS_CLI_PATH};
  shell_args.insert(shell_args.end(), args.begin(), args.end());
  return run_command("/bin/sh", shell_args);
}

// Bad input: one line on standard error naming the file and the problem, exit code 2.
inline void expect_bad_input(const std::vector<std::string>& args, const std::string& message) {
  const CommandResult r = sphys_cli(args);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_THAT(r.err, testing::HasSubstr(message));
}

// The exact standard error of a command that must fail with bad input, and its exit code 2.
inline void expect_refused(const std::vector<std::string>& args, const std::string& err) {
  const CommandResult r = sphys_cli(args);
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_EQ(r.err, err);
}

// The lines of a text file the command wrote; none if it is missing.
inline std::vector<std::string> read_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Temporary files the atomic writers left in `dir`.
inline std::vector<std::filesystem::path> temporary_files_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> found;
  for (const std::filesystem::path& file : files_in(dir)) {
    if (file.extension() == ".tmp") found.push_back(file);
  }
  return found;
}

// Points the command line at one sphere-tree cache for the whole test program (never the user's),
// so that a tree is built once however many tests use it. Removed when the program ends. Call it
// in each test: another test may have moved SPHYS_CACHE_DIR.
inline void use_shared_tree_cache() {
  struct Cache {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("sphys_cli_test_cache_" + std::to_string(getpid()));
    Cache() { std::filesystem::create_directories(path); }
    ~Cache() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Cache cache;
  setenv("SPHYS_CACHE_DIR", cache.path.c_str(), 1);
}

}  // namespace sphys::test
