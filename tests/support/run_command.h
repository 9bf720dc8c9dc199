#pragma once

#include <string>
#include <vector>

namespace sphys::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // standard output
  std::string err;  // standard error
};

// Runs a program with arguments (no shell; a name without a slash is looked up in PATH),
// capturing its output streams and exit code.
CommandResult run_command(const std::string& program, const std::vector<std::string>& args);

}  // namespace sphys::test
