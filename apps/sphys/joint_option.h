#pragma once

// Joint values on the command line as NAME=VALUE (`sphys view --joint`, `sphys query --joint`
// and `--to`).

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sphys/robot_model.h"

namespace sphys::cli {

// One NAME=VALUE, the value in rad or m (NaN and infinities are read, for the checks to refuse by
// name). Throws sphys::Error naming `option` for any other text.
[[nodiscard]] std::pair<std::string, double> parse_joint(std::string_view option,
                                                         const std::string& text);

// Sets each NAME=VALUE of `given` in `values` (one per joint of `model`, in its order). Throws
// sphys::Error naming `option` and the name for a joint the model does not move (listing those it
// does) and for a joint given twice.
void set_joint_values(const RobotModel& model, std::string_view option,
                      const std::vector<std::string>& given, std::vector<double>& values);

}  // namespace sphys::cli
