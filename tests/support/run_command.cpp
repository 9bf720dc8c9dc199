#include "support/run_command.h"

#include <array>
#include <csignal>
#include <fcntl.h>
#include <spawn.h>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace sphys::test {
namespace {

std::string drain(int fd) {
  std::string text;
  std::array<char, 4096> buffer{};
  ssize_t n = 0;
  while ((n = read(fd, buffer.data(), buffer.size())) > 0) {
    text.append(buffer.data(), static_cast<std::size_t>(n));
  }
  close(fd);
  return text;
}

}  // namespace

RunningCommand::RunningCommand(const std::string& program, const std::vector<std::string>& args) {
  // Output goes to temporary files rather than pipes so a chatty child cannot block on a full
  // pipe while we wait for it.
  char out_name[] = "/tmp/sphys_cmd_out_XXXXXX";
  char err_name[] = "/tmp/sphys_cmd_err_XXXXXX";
  out_fd_ = mkstemp(out_name);
  err_fd_ = mkstemp(err_name);
  if (out_fd_ < 0 || err_fd_ < 0) throw std::runtime_error("cannot create capture files");
  out_name_ = out_name;
  err_name_ = err_name;

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_fd_, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_fd_, STDERR_FILENO);
  // The program gets its three streams and nothing else (neither the capture files nor what the
  // test runner left open), so that a test may count on the descriptors it has (`ulimit -n`).
  posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);

  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  const int spawn_error =
      posix_spawnp(&pid_, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    pid_ = -1;
    throw std::runtime_error("cannot start " + program);
  }
}

RunningCommand::~RunningCommand() {
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    (void)wait();
  }
  if (out_fd_ >= 0) close(out_fd_);
  if (err_fd_ >= 0) close(err_fd_);
  if (!out_name_.empty()) unlink(out_name_.c_str());
  if (!err_name_.empty()) unlink(err_name_.c_str());
}

CommandResult RunningCommand::wait() {
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  lseek(out_fd_, 0, SEEK_SET);
  lseek(err_fd_, 0, SEEK_SET);
  result.out = drain(out_fd_);
  result.err = drain(err_fd_);
  out_fd_ = -1;
  err_fd_ = -1;
  unlink(out_name_.c_str());
  unlink(err_name_.c_str());
  out_name_.clear();
  err_name_.clear();
  return result;
}

CommandResult run_command(const std::string& program, const std::vector<std::string>& args) {
  RunningCommand command(program, args);
  return command.wait();
}

}  // namespace sphys::test
