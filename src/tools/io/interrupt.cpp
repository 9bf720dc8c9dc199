#include "sphys/tools/interrupt.h"

#include <csignal>

namespace sphys::tools {
namespace {

// Written by the handler, read by the loops: nothing else is safe to do in a handler.
volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_signal(int signal) { g_signal = signal; }

}  // namespace

void catch_interruptions() {
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the second signal takes the default action. SA_RESTART: a read or write the
  // signal lands in goes on, and the loop notices the signal at its next check.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interruption_signal() { return g_signal; }

void throw_if_interrupted() {
  if (const int signal = g_signal; signal != 0) throw Interrupted(signal);
}

}  // namespace sphys::tools
