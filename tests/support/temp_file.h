#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sphys::test {

// A scratch directory unique to the running test and process, removed with the object.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  // Writes `content` byte for byte to `name` inside the directory and returns its path.
  std::filesystem::path write(std::string_view name, std::string_view content) const;

 private:
  std::filesystem::path path_;
};

// The whole content of a file, byte for byte (empty when it cannot be read).
[[nodiscard]] std::string read_whole(const std::filesystem::path& path);
// The entries of a directory, in no particular order.
[[nodiscard]] std::vector<std::filesystem::path> files_in(const std::filesystem::path& directory);

}  // namespace sphys::test
