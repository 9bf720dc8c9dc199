// The names the command line and Python take for a response mode, a contact set and a ground,
// and give back in reports: those of the settings table's choices, apart from the scene reader.

#include <algorithm>
#include <span>
#include <string>
#include <string_view>

#include "io/shown_text.h"
#include "sphys/error.h"
#include "sphys/settings_table.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {
namespace {

// The index of `name` among the choices of an enum setting, else "unknown <what> '<name>';
// <what>s: a, b", for names given on the command line.
std::size_t parse_name(std::string_view name, const Setting& setting, std::string_view what) {
  const std::span<const std::string_view> names = setting.choices;
  const auto found = std::find(names.begin(), names.end(), name);
  if (found != names.end()) return static_cast<std::size_t>(found - names.begin());
  std::string message = "unknown ";
  message += what;
  message += " '";
  message += name;
  message += "'; ";
  message += what;
  message += "s: ";
  message += joined(names);
  throw Error(message);
}

}  // namespace

std::string_view response_mode_name(ResponseMode mode) {
  return setting_of("response").choices[static_cast<std::size_t>(mode)];
}

ResponseMode parse_response_mode(std::string_view name) {
  return static_cast<ResponseMode>(parse_name(name, setting_of("response"), "response mode"));
}

GroundSpec::Kind parse_ground_option(std::string_view name, std::string_view option) {
  if (name == "octree") return GroundSpec::Kind::kOctreeBox;
  if (name == "plane") return GroundSpec::Kind::kPlane;
  std::string message(option);
  message += " must be octree or plane, got '";
  message += name;
  message += "'";
  throw Error(message);
}

std::string_view contact_set_name(ContactSet contacts) {
  return setting_of("solver.contacts").choices[static_cast<std::size_t>(contacts)];
}

ContactSet parse_contact_set(std::string_view name) {
  return static_cast<ContactSet>(parse_name(name, setting_of("solver.contacts"), "contact set"));
}

}  // namespace sphys::tools
