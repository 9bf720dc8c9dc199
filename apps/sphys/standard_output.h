#pragma once

#include <string_view>

namespace sphys::cli {

// Writes `text` (a --json document, a report) to standard output at once and checks that it got
// there: a full disk or a closed pipe is sphys::Error "standard output: cannot write: <the
// system's reason>", never a silent success.
void print_output(std::string_view text);

// Writes out whatever a command printed with printf and not yet flushed, checked as above; main
// calls it after every command.
void finish_output();

}  // namespace sphys::cli
