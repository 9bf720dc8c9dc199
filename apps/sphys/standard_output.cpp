#include "standard_output.h"

#include <cerrno>
#include <cstdio>

#include "sphys/error.h"
#include "sphys/tools/system_reason.h"

namespace sphys::cli {
namespace {

[[noreturn]] void fail(int error_number) {
  throw Error("standard output: cannot write: " + tools::system_reason(error_number));
}

}  // namespace

void print_output(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size()) fail(errno);
  finish_output();
}

void finish_output() {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return;
  if (errno != 0) fail(errno);
  // The error flag of a write that failed before this call, whose errno is gone.
  throw Error("standard output: cannot write: an earlier write failed");
}

}  // namespace sphys::cli
