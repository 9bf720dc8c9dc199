// The names of the construction methods, apart from the construction itself: the scene reader
// (and with it the fuzzers) uses them without the tree builders.
#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "sphys/error.h"
#include "sphys/tools/build_tree.h"

namespace sphys::tools {
namespace {

constexpr std::array<std::pair<BuildMethod, std::string_view>, 9> kMethodNames{{
    {BuildMethod::Octree, "octree"},
    {BuildMethod::Grid, "grid"},
    {BuildMethod::Spawn, "spawn"},
    {BuildMethod::Hubbard, "hubbard"},
    {BuildMethod::Merge, "merge"},
    {BuildMethod::Burst, "burst"},
    {BuildMethod::Expand, "expand"},
    {BuildMethod::Combined, "combined"},
    {BuildMethod::Tight, "tight"},
}};

}  // namespace

std::string_view method_name(BuildMethod method) {
  for (const auto& [m, name] : kMethodNames) {
    if (m == method) return name;
  }
  return "unknown";
}

BuildMethod parse_method(std::string_view name) {
  std::string valid;
  for (const auto& [method, method_name] : kMethodNames) {
    if (method_name == name) return method;
    valid += (valid.empty() ? "" : ", ") + std::string(method_name);
  }
  throw Error("unknown sphere-tree method '" + std::string(name) + "' (valid: " + valid + ")");
}

}  // namespace sphys::tools
