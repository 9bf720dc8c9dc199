#include "shown_text.h"

#include <cctype>
#include <cstddef>

namespace sphys::tools {

std::string shown(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string out(text.substr(0, kMaxShown));
  for (char& c : out) {
    if (std::isprint(static_cast<unsigned char>(c)) == 0) c = '?';
  }
  if (text.size() > kMaxShown) out += "...";
  return "'" + out + "'";
}

std::string joined(std::span<const std::string_view> names) {
  std::string out;
  for (const std::string_view name : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}  // namespace sphys::tools
