// libFuzzer target: the .sph reader on the bytes.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "sphys/error.h"
#include "sphys/tools/sph_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    (void)sphys::tools::read_sph(in, "fuzz.sph");
  } catch (const sphys::Error&) {
    // Refused with a message: what a bad file should get. Anything else escapes and is a finding.
  }
  return 0;
}
