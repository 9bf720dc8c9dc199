// libFuzzer target: read_recording on the bytes, through a scratch file (it reads a path).

#include <cstddef>
#include <cstdint>

#include "scratch_file.h"
#include "sphys/error.h"
#include "sphys/tools/recording.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sphys::fuzz::ScratchFile file(".sphysrec");
  try {
    (void)sphys::tools::read_recording(file.write(data, size));
  } catch (const sphys::Error&) {
    // Refused with a message: what a bad file should get. Anything else escapes and is a finding.
  }
  return 0;
}
