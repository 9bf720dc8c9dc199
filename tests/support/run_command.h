#pragma once

#include <string>
#include <sys/types.h>
#include <vector>

namespace sphys::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // standard output
  std::string err;  // standard error
};

// A program started with arguments (no shell; a name without a slash is looked up in PATH),
// its output streams going to scratch files, for a test that must act while it runs (send it a
// signal). wait() collects its exit code and output; the destructor kills and reaps a program
// never waited for.
class RunningCommand {
 public:
  RunningCommand(const std::string& program, const std::vector<std::string>& args);
  ~RunningCommand();
  RunningCommand(const RunningCommand&) = delete;
  RunningCommand& operator=(const RunningCommand&) = delete;

  [[nodiscard]] pid_t pid() const { return pid_; }
  // Waits for the program to end. A program a signal ended reads as exit code 128 + the signal.
  CommandResult wait();

 private:
  pid_t pid_ = -1;
  int out_fd_ = -1;
  int err_fd_ = -1;
  std::string out_name_;
  std::string err_name_;
};

// Runs a program to its end, capturing its output streams and exit code.
CommandResult run_command(const std::string& program, const std::vector<std::string>& args);

}  // namespace sphys::test
