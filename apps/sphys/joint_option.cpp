#include "joint_option.h"

#include <algorithm>
#include <stdexcept>

#include "sphys/error.h"

namespace sphys::cli {

std::pair<std::string, double> parse_joint(std::string_view option, const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw Error(std::string(option) + ": expected NAME=VALUE, got \"" + text + "\"");
  }
  try {
    std::size_t used = 0;
    const double value = std::stod(text.substr(equals + 1), &used);
    if (used != text.size() - equals - 1) throw std::invalid_argument(text);
    return {text.substr(0, equals), value};
  } catch (const std::logic_error&) {
    throw Error(std::string(option) + ": \"" + text.substr(equals + 1) + "\" is not a number");
  }
}

void set_joint_values(const RobotModel& model, std::string_view option,
                      const std::vector<std::string>& given, std::vector<double>& values) {
  std::vector<bool> set(model.joints.size(), false);
  for (const std::string& text : given) {
    const auto [name, value] = parse_joint(option, text);
    const auto joint = std::ranges::find_if(
        model.joints, [&](const RobotModel::Joint& j) { return j.name == name; });
    if (joint == model.joints.end()) {
      std::string moving;
      for (const RobotModel::Joint& j : model.joints) {
        moving += (moving.empty() ? "" : ", ") + j.name;
      }
      throw Error(std::string(option) + ": robot '" + model.name + "' has no moving joint '" +
                  name + "' (its moving joints: " + moving + ")");
    }
    const auto j = static_cast<std::size_t>(joint - model.joints.begin());
    if (set[j]) throw Error(std::string(option) + ": joint '" + name + "' is given twice");
    set[j] = true;
    values[j] = value;
  }
}

}  // namespace sphys::cli
