#pragma once

// The readers that take a path get each fuzz input through one scratch file, rewritten per input:
// the file's name ends in the extension that picks the reader.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace sphys::fuzz {

// A file in the temporary directory, unique to this process, removed with the object.
class ScratchFile {
 public:
  explicit ScratchFile(std::string_view extension);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Replaces the file's content with the bytes and returns its path.
  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size);

 private:
  std::filesystem::path path_;
};

}  // namespace sphys::fuzz
