#include "sphys/tools/note.h"

#include <cstdio>
#include <string>

namespace sphys::tools {

void note(std::string_view text) {
  // One call, so that notes from two threads never interleave within a line.
  const std::string line = "sphys: note: " + std::string(text) + "\n";
  std::fputs(line.c_str(), stderr);
}

}  // namespace sphys::tools
