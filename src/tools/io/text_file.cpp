#include "sphys/tools/text_file.h"

#include <ostream>

#include "atomic_file.h"

namespace sphys::tools {

void write_text_file(const std::filesystem::path& path, std::string_view text) {
  write_file_atomically(path, [text](std::ostream& out) {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace sphys::tools
