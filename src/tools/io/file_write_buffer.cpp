#include "file_write_buffer.h"

#include <cerrno>
#include <unistd.h>

namespace sphys::tools {

FileWriteBuffer::FileWriteBuffer(int fd) : fd_(fd) {
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

FileWriteBuffer::~FileWriteBuffer() {
  if (fd_ >= 0) ::close(fd_);
}

void FileWriteBuffer::fail(int error_number) {
  if (error_ == 0) error_ = error_number;
}

bool FileWriteBuffer::flush_buffer() {
  const char* next = pbase();
  const char* const end = pptr();
  // After a failure nothing more is written: the first reason is the one reported.
  while (error_ == 0 && next < end) {
    const ssize_t written = ::write(fd_, next, static_cast<std::size_t>(end - next));
    if (written < 0) {
      if (errno != EINTR) fail(errno);
    } else {
      next += written;
    }
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return error_ == 0;
}

FileWriteBuffer::int_type FileWriteBuffer::overflow(int_type ch) {
  if (!flush_buffer()) return traits_type::eof();
  if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
  *pptr() = traits_type::to_char_type(ch);
  pbump(1);
  return ch;
}

int FileWriteBuffer::sync() { return flush_buffer() ? 0 : -1; }

FileWriteBuffer::pos_type FileWriteBuffer::seekoff(off_type offset,
                                                   std::ios_base::seekdir direction,
                                                   std::ios_base::openmode which) {
  if (!(which & std::ios_base::out) || !flush_buffer()) return pos_type(off_type(-1));
  const int whence = direction == std::ios_base::beg   ? SEEK_SET
                     : direction == std::ios_base::cur ? SEEK_CUR
                                                       : SEEK_END;
  const off_t position = ::lseek(fd_, offset, whence);
  if (position < 0) {
    fail(errno);
    return pos_type(off_type(-1));
  }
  return pos_type(position);
}

FileWriteBuffer::pos_type FileWriteBuffer::seekpos(pos_type position,
                                                   std::ios_base::openmode which) {
  return seekoff(off_type(position), std::ios_base::beg, which);
}

bool FileWriteBuffer::close() {
  if (fd_ < 0) return error_ == 0;
  flush_buffer();
  // Some file systems (NFS, quotas) report a failed write only here.
  if (::close(fd_) != 0) fail(errno);
  fd_ = -1;
  return error_ == 0;
}

}  // namespace sphys::tools
