#include "atomic_file.h"

#include <cassert>
#include <cerrno>
#include <fcntl.h>
#include <system_error>
#include <utility>

#include "file_write_buffer.h"
#include "sphys/error.h"
#include "sphys/tools/system_reason.h"
#include "temporary_files.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

fs::path directory_of(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// A name for the temporary file, in a directory cleared of the temporaries of ended processes.
fs::path fresh_temporary(const fs::path& target) {
  remove_orphaned_temporaries(directory_of(target));
  return temporary_sibling(target);
}

// The temporary file, new and open for writing; else sphys::Error naming the target.
int create_temporary(const fs::path& target, const fs::path& temporary) {
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd >= 0) return fd;
  const int reason = errno;
  std::error_code ec;
  if (reason == ENOENT && !fs::is_directory(directory_of(target), ec)) {
    throw Error::in_file(target, "cannot write: the directory does not exist");
  }
  throw Error::in_file(target, "cannot create a file in its directory: " + system_reason(reason));
}

}  // namespace

AtomicFile::AtomicFile(fs::path path)
    : path_(std::move(path)),
      temporary_(fresh_temporary(path_)),
      buffer_(std::make_unique<FileWriteBuffer>(create_temporary(path_, temporary_))),
      out_(buffer_.get()) {}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  buffer_->close();
  std::error_code ignored;
  fs::remove(temporary_, ignored);
}

void AtomicFile::check_written() const {
  if (buffer_->error() != 0) {
    throw Error::in_file(path_, "cannot write the file: " + system_reason(buffer_->error()));
  }
  // A stream error without a system error: a writer's own formatting failed.
  if (!out_) throw Error::in_file(path_, "cannot write the file");
}

void AtomicFile::commit() {
  assert(!committed_);
  // Closing writes the last buffered bytes, which is where a full disk often shows.
  buffer_->close();
  check_written();
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) throw Error::in_file(path_, "cannot replace the file: " + system_reason(ec.value()));
  committed_ = true;
}

void write_file_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  AtomicFile file(path);
  write(file.stream());
  file.commit();
}

}  // namespace sphys::tools
