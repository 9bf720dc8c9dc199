// Writes the test robot of the spherize tests into a folder, for trying the commands on it by
// hand and for the picture in docs/robots.md:
//   sphys_write_test_robot DIR
// prints the URDF's path and the --package option it needs.
#include <cstdio>
#include <exception>
#include <filesystem>

#include "support/test_robot.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sphys_write_test_robot DIR\n");
    return 2;
  }
  try {
    std::filesystem::create_directories(argv[1]);
    const sphys::test::TestRobot robot =
        sphys::test::write_test_robot(argv[1], sphys::test::standard_test_robot());
    std::printf("%s --package %s\n", robot.urdf.c_str(), robot.package_option.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sphys_write_test_robot: %s\n", error.what());
    return 1;
  }
  return 0;
}
