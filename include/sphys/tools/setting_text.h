#pragma once

// The world's settings as a person types and reads them: `--set name=value` on the command line
// and keyword arguments in Python, and the valid values in --help and Python's settings table.
// The settings themselves and their validation are the runtime's (sphys/settings_table.h).

#include <string>
#include <string_view>

#include "sphys/settings_table.h"

// In namespace sphys beside Setting, so that callers find them by their arguments.
namespace sphys {

// Sets the field named as in Setting::field ("solver.soft_substeps") from text as a command line
// gives it: a number, true or false, or a choice's name. Throws sphys::Error for an unknown field,
// a vector, or text that is none of these, naming `source` (e.g. "--set"); the range is
// check_world_settings' to check.
void set_setting_from_text(WorldSettings& settings, std::string_view field, std::string_view text,
                           std::string_view source);

// "1 to 64", ">= 0", "> 0", "0 to 1", "finite", "paper or plausible", "true or false": the valid
// values as a person reads them.
[[nodiscard]] std::string range_text(const Setting& setting);

// A --help text for a command-line option that sets this setting: its documentation, valid values
// and unit ("... Valid: 1 to 64; unit: substeps."). The option's own default is the command's to
// show: it need not be the runtime's.
[[nodiscard]] std::string option_help(const Setting& setting);

}  // namespace sphys
