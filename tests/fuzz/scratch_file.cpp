#include "scratch_file.h"

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <unistd.h>

namespace sphys::fuzz {

ScratchFile::ScratchFile(std::string_view extension)
    : path_(std::filesystem::temp_directory_path() /
            ("sphys_fuzz_" + std::to_string(getpid()) + std::string(extension))) {}

ScratchFile::~ScratchFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

const std::filesystem::path& ScratchFile::write(const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  // A fuzzer that cannot write its input tests nothing: stop rather than report clean runs.
  if (!out) throw std::runtime_error("cannot write the fuzz input " + path_.string());
  return path_;
}

}  // namespace sphys::fuzz
