#pragma once

#include <string>

namespace sphys::tools {

// What the system says went wrong, as strerror words it ("No space left on device", "Too many
// open files"): every message about a file sphys could not create, write or replace ends with
// it, so that a person learns the cause rather than a guess.
[[nodiscard]] std::string system_reason(int error_number);

}  // namespace sphys::tools
