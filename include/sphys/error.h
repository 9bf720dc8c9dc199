#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sphys {

// The one exception type sphys throws for bad input: a missing or corrupt file, a malformed
// record, an impossible parameter. Its message names where the problem is (file, line or JSON
// path) and what is wrong, ready to be shown to a person as one line. The command line maps it to
// exit code 2; any other exception is an internal error (exit code 1).
class Error : public std::runtime_error {
 public:
  // `message`: the whole line to show, where and what (the helpers below compose it).
  explicit Error(const std::string& message);

  // "<file>: <problem>"
  static Error in_file(const std::filesystem::path& file, std::string_view problem);
  // "<file>:<line>: <problem>"  (lines count from 1)
  static Error at_line(const std::filesystem::path& file, std::size_t line,
                       std::string_view problem);
  // "<file>: <json path>: <problem>"  (e.g. "/bodies/3/density")
  static Error at_json_path(const std::filesystem::path& file, std::string_view json_path,
                            std::string_view problem);
};

}  // namespace sphys
