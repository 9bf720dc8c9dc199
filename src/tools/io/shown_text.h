#pragma once

#include <span>
#include <string>
#include <string_view>

namespace sphys::tools {

// Text from a file as a message may show it, in single quotes: a file may hold anything, so
// unprintable bytes become '?' and more than 40 characters end in "...".
[[nodiscard]] std::string shown(std::string_view text);

// Names as a message lists them: "paper, plausible".
[[nodiscard]] std::string joined(std::span<const std::string_view> names);

}  // namespace sphys::tools
