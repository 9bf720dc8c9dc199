// Inputs the readers' fuzzers (tests/fuzz, scripts/fuzz) found to crash sphys, hang it or exhaust
// its memory: each is now refused through the command line with its message and exit code 2.

#include <bit>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/temp_file.h"

namespace sphys::fuzz_findings_test {

using test::expect_refused;

// A little-endian unsigned integer of `bytes` bytes, as the recording header stores it.
std::string little_endian(std::uint64_t value, int bytes) {
  std::string out;
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xff);
  return out;
}

// A recording header (docs/file-formats.md) with no metadata.
std::string recording_header(std::uint32_t body_count, std::uint32_t frame_count) {
  return "SPHYSREC" + little_endian(1, 4) + little_endian(body_count, 4) +
         little_endian(std::bit_cast<std::uint64_t>(1.0 / 60.0), 8) +
         little_endian(frame_count, 4) + little_endian(0, 4);
}

// Found by fuzz_recording: a recording of no frames sized its frame buffer by the body count
// alone, 28 bytes times 4 billion (120 GB), and died of bad_alloc (exit 1) before its scene was
// read.
TEST(FuzzFindings, AnEmptyRecordingOfBillionsOfBodiesAllocatesNoFrame) {
  const test::TempDir dir;
  const std::string recording =
      dir.write("empty.sphysrec", recording_header(0xffff0003, 0)).string();
  expect_refused({"export", recording, "--gltf", (dir.path() / "out.glb").string()},
                 "sphys: error: " + recording + ": its scene cannot be read: " + recording +
                     ":1: column 1: not valid JSON: syntax error while parsing value - unexpected "
                     "end of input; expected '[', '{', or a literal\n");
}

// Found by fuzz_stl while out-of-memory errors were told from assimp's messages by their text: an
// STL file whose own words hold "bad_alloc" was reported as sphys running out of memory (and
// aborted the fuzzer). assimp's caught exception itself now decides.
TEST(FuzzFindings, AMeshThatSaysBadAllocIsBadInput) {
  const test::TempDir dir;
  const std::string stl = dir.write("named.stl", "solid bad_alloc\nendsolid bad_alloc\n").string();
  expect_refused(
      {"mesh-info", stl},
      "sphys: error: " + stl + ": Validation failed: The mesh bad_alloc contains no vertices\n");
}

}  // namespace sphys::fuzz_findings_test
