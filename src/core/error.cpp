#include "sphys/error.h"

#include <string>

namespace sphys {

Error::Error(const std::string& message) : std::runtime_error(message) {}

Error Error::in_file(const std::filesystem::path& file, std::string_view problem) {
  return Error(file.string() + ": " + std::string(problem));
}

Error Error::at_line(const std::filesystem::path& file, std::size_t line,
                     std::string_view problem) {
  return Error(file.string() + ":" + std::to_string(line) + ": " + std::string(problem));
}

Error Error::at_json_path(const std::filesystem::path& file, std::string_view json_path,
                          std::string_view problem) {
  return Error(file.string() + ": " + std::string(json_path) + ": " + std::string(problem));
}

}  // namespace sphys
