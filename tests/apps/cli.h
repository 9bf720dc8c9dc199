#pragma once

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/run_command.h"

namespace sphys::test {

// The sphys program built with the tests (its path comes from CMake).
inline CommandResult sphys_cli(const std::vector<std::string>& args) {
  return run_command(SPHYS_CLI_PATH, args);
}

// Bad input: one line on standard error naming the file and the problem, exit code 2.
inline void expect_bad_input(const std::vector<std::string>& args, const std::string& message) {
  const CommandResult r = sphys_cli(args);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_THAT(r.err, testing::HasSubstr(message));
}

}  // namespace sphys::test
