#include "sphys/error.h"

#include <gtest/gtest.h>

namespace sphys {
namespace {

TEST(Error, NamesFileLineAndJsonPath) {
  EXPECT_STREQ(Error::in_file("a/b.obj", "no such file").what(), "a/b.obj: no such file");
  EXPECT_STREQ(Error::at_line("t.sph", 12, "radius is not a number").what(),
               "t.sph:12: radius is not a number");
  EXPECT_STREQ(Error::at_json_path("s.json", "/bodies/3/density", "must be positive").what(),
               "s.json: /bodies/3/density: must be positive");
}

}  // namespace
}  // namespace sphys
