// libFuzzer target: the scene reader on the bytes as JSON text. Mesh and .sph paths in it resolve
// against the temporary directory; the reader only checks that they name regular files.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "sphys/error.h"
#include "sphys/tools/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path name = std::filesystem::temp_directory_path() / "fuzz.json";
  try {
    (void)sphys::tools::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size),
                                    name);
  } catch (const sphys::Error&) {
    // Refused with a message: what a bad file should get. Anything else escapes and is a finding.
  }
  return 0;
}
