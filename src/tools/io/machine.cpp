#include "sphys/tools/machine.h"

#include <cctype>
#include <fstream>
#include <thread>

namespace sphys::tools {

Machine this_machine() {
  Machine machine{"unknown processor", std::thread::hardware_concurrency()};
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.starts_with("model name")) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) {
        machine.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
      }
      break;
    }
  }
  return machine;
}

std::string machine_description() {
  const Machine machine = this_machine();
  return machine.cpu + ", " + std::to_string(machine.hardware_threads) + " hardware threads";
}

std::string machine_folder() {
  const Machine machine = this_machine();
  std::string folder;
  for (const char c : machine.cpu) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
      folder += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!folder.empty() && folder.back() != '-') {
      folder += '-';
    }
  }
  if (!folder.empty() && folder.back() != '-') folder += '-';
  return folder + std::to_string(machine.hardware_threads) + "t";
}

}  // namespace sphys::tools
