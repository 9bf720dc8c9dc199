#pragma once

#include <string_view>

namespace sphys::tools {

// Something a person should know that does not stop the work (a damaged cache entry rebuilt, a
// cache that cannot be used, a temporary file of an ended process removed): one line
// "sphys: note: <text>" on standard error.
void note(std::string_view text);

}  // namespace sphys::tools
