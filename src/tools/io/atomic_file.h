#pragma once

// Files that appear whole or not at all: the bytes go to a temporary file next to the target
// (temporary_files.h: its name carries the process id, so that a later run can remove it should
// this process be killed), which is renamed over the target once everything was written. A
// reader never sees a half-written file, and a failure (or an exception thrown while writing)
// leaves neither the temporary nor a partial target behind.

#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>

namespace sphys::tools {

class FileWriteBuffer;

// For writers that stream more than they should hold in memory. Errors are sphys::Error naming
// the target and ending with the system's reason: "cannot write: the directory does not exist",
// "cannot create a file in its directory: Too many open files", "cannot write the file: No space
// left on device", "cannot replace the file: Permission denied".
class AtomicFile {
 public:
  // Creates the temporary file, having first removed the temporary files of ended processes
  // from the target's directory.
  explicit AtomicFile(std::filesystem::path path);
  // Removes the temporary file unless commit() moved it into place.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Where the bytes go until commit(). Seeking back to patch a header is fine.
  [[nodiscard]] std::ostream& stream() { return out_; }
  // The target, for messages.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  // Throws if a write to stream() has failed so far, so that a long writer can stop at the first
  // failure rather than at commit().
  void check_written() const;
  // Closes the temporary file and renames it over the target, replacing an existing file.
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  std::unique_ptr<FileWriteBuffer> buffer_;
  std::ostream out_;
  bool committed_ = false;
};

// Writes the file whole or not at all: `write` fills the stream (binary mode), then the file is
// moved into place. Whatever `write` throws passes through, leaving nothing behind.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace sphys::tools
