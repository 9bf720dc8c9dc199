#pragma once

#include <exception>

namespace sphys::tools {

// Ctrl-C (SIGINT) and `kill` (SIGTERM) during a long command. The signal handler only records
// the signal; long loops call throw_if_interrupted() once per frame (or per progress report),
// which throws Interrupted. Unwinding then removes the temporary files of unfinished outputs
// (AtomicFile) while files already finished stay whole, and the command line exits with
// 128 + the signal's number (130 for SIGINT, 143 for SIGTERM) after printing
// "sphys: interrupted".
class Interrupted : public std::exception {
 public:
  // For the signal received (its number, e.g. SIGINT).
  explicit Interrupted(int signal) : signal_(signal) {}
  // "interrupted".
  [[nodiscard]] const char* what() const noexcept override { return "interrupted"; }
  // The signal's number.
  [[nodiscard]] int signal() const { return signal_; }
  // The exit code a shell expects of a program a signal ended: 128 + its number.
  [[nodiscard]] int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

// Installs the handlers for SIGINT and SIGTERM. Each handles one signal: a second one ends the
// process at once, as by default, for when a step takes too long to reach a check.
void catch_interruptions();

// The signal received since catch_interruptions(), or 0.
[[nodiscard]] int interruption_signal();

// Throws Interrupted when a signal was received.
void throw_if_interrupted();

}  // namespace sphys::tools
