#include "temporary_files.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <unistd.h>

#include "sphys/tools/note.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kTag = ".sphys-";
constexpr std::string_view kSuffix = ".tmp";

// The process id in a temporary file's name, or nothing for any other name.
std::optional<pid_t> owner_of(std::string_view name) {
  if (name.size() <= kSuffix.size() || !name.ends_with(kSuffix)) return std::nullopt;
  name.remove_suffix(kSuffix.size());
  const std::size_t tag = name.rfind(kTag);
  if (tag == std::string_view::npos) return std::nullopt;
  const std::string_view rest = name.substr(tag + kTag.size());  // "<pid>-<hex>"
  const std::size_t dash = rest.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::string_view hex = rest.substr(dash + 1);
  if (hex.empty() || !std::all_of(hex.begin(), hex.end(), [](char c) {
        return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
      })) {
    return std::nullopt;
  }
  pid_t pid = 0;
  const auto [end, error] = std::from_chars(rest.data(), rest.data() + dash, pid);
  if (error != std::errc() || end != rest.data() + dash || pid <= 0) return std::nullopt;
  return pid;
}

// ESRCH only: a process this one may not signal (EPERM) is alive.
bool has_ended(pid_t pid) { return ::kill(pid, 0) != 0 && errno == ESRCH; }

// Whether this process has looked at `directory` before (and marks it looked at).
bool seen_before(const fs::path& directory) {
  static std::mutex mutex;
  static std::set<fs::path> seen;
  std::error_code ec;
  fs::path key = fs::absolute(directory, ec);
  if (ec) key = directory;
  const std::scoped_lock lock(mutex);
  return !seen.insert(key.lexically_normal()).second;
}

}  // namespace

fs::path temporary_sibling(const fs::path& target) {
  std::random_device random;
  const std::uint64_t tag = (std::uint64_t{random()} << 32) ^ random();
  std::array<char, 17> hex{};
  const auto result = std::to_chars(hex.data(), hex.data() + hex.size(), tag, 16);
  fs::path sibling = target;
  sibling += kTag;
  sibling += std::to_string(::getpid());
  sibling += "-";
  sibling += std::string_view(hex.data(), static_cast<std::size_t>(result.ptr - hex.data()));
  sibling += kSuffix;
  return sibling;
}

void remove_orphaned_temporaries(const fs::path& directory) {
  const fs::path folder = directory.empty() ? fs::path(".") : directory;
  if (seen_before(folder)) return;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& path = it->path();
    const std::optional<pid_t> owner = owner_of(path.filename().native());
    if (!owner || *owner == ::getpid() || !has_ended(*owner)) continue;
    std::error_code removed;
    if (fs::remove(path, removed)) {
      note("removed " + path.string() + ", a temporary file of process " + std::to_string(*owner) +
           ", which has ended");
    }
  }
}

}  // namespace sphys::tools
