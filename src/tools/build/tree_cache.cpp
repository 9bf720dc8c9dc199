#include "sphys/tools/tree_cache.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <mutex>
#include <set>
#include <string>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

#include "io/input_file.h"
#include "io/temporary_files.h"
#include "sphys/error.h"
#include "sphys/tools/note.h"
#include "sphys/tools/system_reason.h"
#include "sphys/tools/text_file.h"
#include "tree_cache_entry.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// A cache is an optimisation: a folder that cannot be read or written is given up for the rest
// of the process, with one note, and every tree is built.
class UnusableFolders {
 public:
  [[nodiscard]] bool contains(const fs::path& dir) {
    const std::scoped_lock lock(mutex_);
    return folders_.contains(dir);
  }
  void give_up(const fs::path& dir, const std::string& reason) {
    const std::scoped_lock lock(mutex_);
    if (folders_.insert(dir).second) {
      note("the sphere-tree cache " + dir.string() + " cannot be used (" + reason +
           "); going on without it");
    }
  }

 private:
  std::mutex mutex_;
  std::set<fs::path> folders_;
};

UnusableFolders& unusable_folders() {
  static UnusableFolders folders;
  return folders;
}

// The entry's bytes, or the errno of the failure to read them (ENOENT: no entry). Not a regular
// file, or larger than any entry may be: read as an empty, so damaged, entry.
int read_entry(const fs::path& path, std::string& bytes) {
  // O_NONBLOCK: a named pipe under an entry's name must not stop the run.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return errno;
  struct stat info {};
  int error = 0;
  if (::fstat(fd, &info) != 0) {
    error = errno;
  } else if (S_ISREG(info.st_mode) &&
             static_cast<std::uint64_t>(info.st_size) <= kMaxSphereTreeFileBytes) {
    bytes.resize(static_cast<std::size_t>(info.st_size));
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) error = errno;
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    bytes.resize(done);
  }
  ::close(fd);
  return error;
}

// An entry's error without the entry's path in front, for messages that name the entry already.
std::string problem_of(const Error& error, const fs::path& path) {
  const std::string text = error.what();
  const std::string prefix = path.string() + ": ";
  return text.starts_with(prefix) ? text.substr(prefix.size()) : text;
}

// The tree of a usable entry at `path` made for `origin`; nothing when there is none, the
// entry is damaged (noted, to be replaced) or the folder cannot be read (given up).
std::optional<SphereTree> load_entry(const fs::path& dir, const fs::path& path,
                                     const TreeOrigin& origin) {
  std::string bytes;
  if (const int error = read_entry(path, bytes)) {
    if (error != ENOENT) unusable_folders().give_up(dir, system_reason(error));
    return std::nullopt;
  }
  std::string problem;
  try {
    DecodedEntry entry = decode_entry(bytes, path);
    // The name is a hash of the origin, so this differs only where hashes collide.
    if (entry.origin == origin) return std::move(entry.tree);
    problem = "made for another mesh or other parameters";
  } catch (const Error& error) {
    problem = problem_of(error, path);
  }
  note(path.string() + ": a damaged sphere-tree cache entry (" + problem +
       "); rebuilding and replacing it");
  return std::nullopt;
}

void store_entry(const fs::path& dir, const fs::path& path, const TreeOrigin& origin,
                 const SphereTree& tree) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    unusable_folders().give_up(dir, system_reason(ec.value()));
    return;
  }
  try {
    write_text_file(path, encode_entry(origin, tree));
  } catch (const Error& error) {
    unusable_folders().give_up(dir, error.what());
  }
}

}  // namespace

fs::path default_cache_dir() {
  if (const char* dir = std::getenv("SPHYS_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return fs::path(xdg) / "sphys";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return fs::path(home) / ".cache" / "sphys";
  }
  return fs::temp_directory_path() / "sphys-cache";
}

fs::path cache_path(const fs::path& dir, const TriangleMesh& mesh, const BuildOptions& options) {
  return dir / entry_name(origin_of(mesh, options));
}

CachedTree build_sphere_tree_cached(const TriangleMesh& mesh, const BuildOptions& options,
                                    const std::optional<fs::path>& dir) {
  if (!dir || unusable_folders().contains(*dir)) return {build_sphere_tree(mesh, options), false};
  const TreeOrigin origin = origin_of(mesh, options);
  const fs::path path = *dir / entry_name(origin);
  if (std::optional<SphereTree> cached = load_entry(*dir, path, origin)) {
    return {std::move(*cached), true};
  }
  CachedTree built{build_sphere_tree(mesh, options), false};
  if (!unusable_folders().contains(*dir)) store_entry(*dir, path, origin, built.tree);
  return built;
}

std::vector<CacheEntryCheck> check_cache(const fs::path& dir) {
  std::vector<CacheEntryCheck> checks;
  std::error_code ec;
  if (!fs::exists(dir, ec) && !ec) return checks;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!is_entry_name(it->path().filename().native())) continue;
    CacheEntryCheck& check = checks.emplace_back();
    check.path = it->path();
    std::string bytes;
    if (const int error = read_entry(check.path, bytes)) {
      check.problem = "cannot be read: " + system_reason(error);
      continue;
    }
    check.bytes = bytes.size();
    try {
      const DecodedEntry entry = decode_entry(bytes, check.path);
      check.description = entry.origin.method + ", branching " +
                          std::to_string(entry.tree.branching()) + ", depth " +
                          std::to_string(entry.tree.depth()) + " (" +
                          std::to_string(entry.tree.size()) + " spheres)";
    } catch (const Error& error) {
      check.problem = problem_of(error, check.path);
    }
  }
  if (ec) throw Error::in_file(dir, "cannot read the cache folder: " + system_reason(ec.value()));
  std::sort(checks.begin(), checks.end(),
            [](const CacheEntryCheck& a, const CacheEntryCheck& b) { return a.path < b.path; });
  return checks;
}

std::size_t clear_cache(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec) && !ec) return 0;
  remove_orphaned_temporaries(dir);
  std::size_t removed = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!is_entry_name(it->path().filename().native())) continue;
    std::error_code failed;
    fs::remove(it->path(), failed);
    if (failed) {
      throw Error::in_file(it->path(), "cannot remove the file: " + system_reason(failed.value()));
    }
    ++removed;
  }
  if (ec) throw Error::in_file(dir, "cannot read the cache folder: " + system_reason(ec.value()));
  return removed;
}

}  // namespace sphys::tools
