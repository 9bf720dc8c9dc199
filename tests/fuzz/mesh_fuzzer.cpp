// libFuzzer target: load_mesh on a file whose extension (SPHYS_FUZZ_MESH_EXTENSION, one build per
// format) picks the reader: OBJ and STL through assimp, OFF and PLY through sphys's own.

#include <cstddef>
#include <cstdint>

#include "scratch_file.h"
#include "sphys/error.h"
#include "sphys/tools/load_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sphys::fuzz::ScratchFile file(SPHYS_FUZZ_MESH_EXTENSION);
  try {
    (void)sphys::tools::load_mesh(file.write(data, size));
  } catch (const sphys::Error&) {
    // Refused with a message: what a bad file should get. Anything else escapes and is a finding.
  }
  return 0;
}
