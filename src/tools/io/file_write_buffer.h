#pragma once

#include <array>
#include <streambuf>

namespace sphys::tools {

// A stream buffer writing to a POSIX file descriptor that keeps the system's error number of the
// first write, seek or close that failed. std::ofstream reports only that something failed, and
// errno is gone by the time a writer checks the stream; this keeps the reason for the message.
class FileWriteBuffer : public std::streambuf {
 public:
  // Takes ownership of `fd`, open for writing.
  explicit FileWriteBuffer(int fd);
  // Closes the descriptor if close() was not called (errors then go unreported).
  ~FileWriteBuffer() override;
  FileWriteBuffer(const FileWriteBuffer&) = delete;
  FileWriteBuffer& operator=(const FileWriteBuffer&) = delete;

  // Writes what is buffered and closes the descriptor; false (with error() set) if either failed.
  bool close();
  // The errno of the first failure, 0 while everything succeeded.
  [[nodiscard]] int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override;
  int sync() override;
  pos_type seekoff(off_type offset, std::ios_base::seekdir direction,
                   std::ios_base::openmode which) override;
  pos_type seekpos(pos_type position, std::ios_base::openmode which) override;

 private:
  bool flush_buffer();
  void fail(int error_number);

  int fd_;
  int error_ = 0;
  std::array<char, 1 << 16> buffer_{};
};

}  // namespace sphys::tools
