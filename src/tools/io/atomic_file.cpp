#include "atomic_file.h"

#include <array>
#include <cassert>
#include <charconv>
#include <cstdint>
#include <random>
#include <string_view>
#include <system_error>
#include <utility>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// A fresh name next to `target`, so that the final rename stays within one file system.
fs::path temporary_sibling(const fs::path& target) {
  std::random_device random;
  const std::uint64_t tag = (std::uint64_t{random()} << 32) ^ random();
  std::array<char, 17> hex{};
  const auto result = std::to_chars(hex.data(), hex.data() + hex.size(), tag, 16);
  fs::path sibling = target;
  sibling += ".";
  sibling += std::string_view(hex.data(), static_cast<std::size_t>(result.ptr - hex.data()));
  sibling += ".tmp";
  return sibling;
}

}  // namespace

AtomicFile::AtomicFile(fs::path path)
    : path_(std::move(path)),
      temporary_(temporary_sibling(path_)),
      out_(temporary_, std::ios::binary) {
  if (!out_) {
    const fs::path directory = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    std::error_code ec;
    throw Error::in_file(path_, fs::is_directory(directory, ec)
                                    ? "cannot create a file in its directory"
                                    : "cannot write: the directory does not exist");
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void AtomicFile::check_written() const {
  if (!out_) throw Error::in_file(path_, "cannot write the file (is the disk full?)");
}

void AtomicFile::commit() {
  assert(!committed_);
  // Closing flushes the last buffered bytes, which is where a full disk often shows.
  out_.close();
  check_written();
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) throw Error::in_file(path_, "cannot replace the file: " + ec.message());
  committed_ = true;
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  write(file.stream());
  file.commit();
}

}  // namespace sphys::tools
