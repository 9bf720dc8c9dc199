#include "tools/io/input_file.h"

#include <chrono>
#include <fcntl.h>
#include <functional>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/load_mesh.h"
#include "sphys/tools/recording.h"
#include "sphys/tools/scene_file.h"
#include "sphys/tools/sph_file.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

using testing::HasSubstr;

// Every reader of a file, by name, so that each refusal is checked for each of them.
struct InputReader {
  const char* name;
  std::function<void(const fs::path&)> read;
};

const std::vector<InputReader>& input_readers() {
  static const std::vector<InputReader> all = {
      {"mesh.obj", [](const fs::path& p) { (void)load_mesh(p); }},
      {"mesh.stl", [](const fs::path& p) { (void)load_mesh(p); }},
      {"mesh.off", [](const fs::path& p) { (void)load_mesh(p); }},
      {"mesh.ply", [](const fs::path& p) { (void)load_mesh(p); }},
      {"tree.sph", [](const fs::path& p) { (void)read_sph(p); }},
      {"scene.json", [](const fs::path& p) { (void)read_scene_file(p); }},
      {"run.sphysrec", [](const fs::path& p) { (void)read_recording(p); }},
  };
  return all;
}

std::string input_error(const InputReader& reader, const fs::path& path) {
  try {
    reader.read(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// A named pipe used to block open() until a writer came: the readers must refuse it without
// opening it. With no fix this test hangs, so ctest's timeout would end it.
TEST(InputFile, NamedPipesAreRefusedWithoutOpening) {
  const test::TempDir dir;
  for (const InputReader& reader : input_readers()) {
    const fs::path fifo = dir.path() / reader.name;
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(input_error(reader, fifo),
              fifo.string() + ": is a named pipe (FIFO), not a regular file");
  }
}

TEST(InputFile, DevicesAreRefused) {
  for (const InputReader& reader : input_readers()) {
    EXPECT_EQ(input_error(reader, "/dev/zero"), "/dev/zero: is a device, not a regular file")
        << reader.name;
  }
}

// A sparse file takes no disk; read, it cost 15 to 45 s and gigabytes before its error.
TEST(InputFile, FilesOverTheLimitAreRefusedAtOnce) {
  const test::TempDir dir;
  constexpr off_t kTwoGiB = off_t{2} << 30;
  for (const InputReader& reader : input_readers()) {
    const fs::path path = dir.path() / reader.name;
    const int fd = open(path.c_str(), O_CREAT | O_WRONLY, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(ftruncate(fd, kTwoGiB), 0);
    close(fd);
    const std::string error = input_error(reader, path);
    // Recordings may be up to 4 GiB: this one is refused by its header instead.
    if (std::string(reader.name) == "run.sphysrec") {
      EXPECT_THAT(error, HasSubstr("not a sphys recording"));
    } else {
      EXPECT_THAT(error, HasSubstr(path.string() + ": is 2 GiB, more than the "));
    }
  }
  EXPECT_EQ(
      input_error(input_readers()[0], dir.path() / "mesh.obj"),
      (dir.path() / "mesh.obj").string() + ": is 2 GiB, more than the 1 GiB a mesh file may have");
  EXPECT_EQ(input_error(input_readers()[5], dir.path() / "scene.json"),
            (dir.path() / "scene.json").string() +
                ": is 2 GiB, more than the 64 MiB a scene file may have");
}

TEST(InputFile, DirectoriesAndMissingFilesAreNamed) {
  const test::TempDir dir;
  EXPECT_EQ(input_file_problem(dir.path(), InputKind::kMesh), "is a directory, not a mesh file");
  EXPECT_EQ(input_file_problem(dir.path(), InputKind::kRecording),
            "is a directory, not a recording");
  EXPECT_EQ(input_file_problem(dir.path() / "none", InputKind::kScene), "no such file");
  EXPECT_EQ(input_file_problem("", InputKind::kScene), "no file name given");
  EXPECT_EQ(input_file_problem(dir.write("ok.sph", "1 8\n"), InputKind::kSphereTree), std::nullopt);
}

// A scene naming a pipe as a body's mesh is refused when it is read, at the body's JSON path.
TEST(InputFile, ASceneNamingAPipeIsRefusedAtTheBody) {
  const test::TempDir dir;
  ASSERT_EQ(mkfifo((dir.path() / "pipe.obj").c_str(), 0600), 0);
  const fs::path scene = dir.write(
      "scene.json", R"({"format": "sphys-scene", "version": 1, "bodies": [{"mesh": "pipe.obj"}]})");
  try {
    (void)read_scene_file(scene);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              scene.string() + ": /bodies/0/mesh: is a named pipe (FIFO), not a regular file: " +
                  (dir.path() / "pipe.obj").string());
  }
}

// An OFF header claiming a billion vertices ended in std::bad_alloc.
TEST(InputFile, OffVertexCountsTheFileCannotHoldAreRefused) {
  const test::TempDir dir;
  const fs::path off = dir.write("huge.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(input_error(input_readers()[2], off),
            off.string() +
                ":2: the header announces 1000000000 vertices, more than the file's 45 "
                "bytes can hold");
  // Faces are not allocated ahead: too many end where the file does.
  const fs::path faces = dir.write("faces.off", "OFF 3 999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(input_error(input_readers()[2], faces),
            faces.string() + ":5: file ends early: expected a face");
}

}  // namespace
}  // namespace sphys::tools
