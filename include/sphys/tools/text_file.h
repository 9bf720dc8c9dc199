#pragma once

#include <filesystem>
#include <string_view>

namespace sphys::tools {

// Writes `text` to `path` whole or not at all (a temporary file renamed into place). Throws
// sphys::Error naming the file when it cannot be written.
void write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace sphys::tools
