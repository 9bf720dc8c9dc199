// The temporary files next to outputs carry their process's id, so that a later run into the same
// folder can remove those a killed process left; and a failed write says what the system said.

#include "tools/io/temporary_files.h"

#include <cerrno>
#include <fcntl.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "sphys/tools/text_file.h"
#include "support/temp_file.h"
#include "tools/io/atomic_file.h"
#include "tools/io/file_write_buffer.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// The id of a process that has ended and been reaped.
pid_t ended_process() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

// The name temporary_sibling() would give `target` in process `pid`.
fs::path temporary_of(const fs::path& target, pid_t pid) {
  return target.string() + ".sphys-" + std::to_string(pid) + "-9f3a6c0d2b1e4f57.tmp";
}

TEST(TemporaryFiles, NameCarriesTheProcessId) {
  const fs::path name = temporary_sibling("/out/frames.csv");
  EXPECT_EQ(name.parent_path(), "/out");
  EXPECT_THAT(name.filename().string(),
              testing::StartsWith("frames.csv.sphys-" + std::to_string(getpid()) + "-"));
  EXPECT_EQ(name.extension(), ".tmp");
  EXPECT_NE(name, temporary_sibling("/out/frames.csv"));
}

TEST(TemporaryFiles, AWriteRemovesOnlyTheTemporariesOfEndedProcesses) {
  const test::TempDir dir;
  const pid_t ended = ended_process();
  const fs::path orphan = dir.write(temporary_of("recording.sphysrec", ended).string(), "x");
  const fs::path running = dir.write(temporary_of("frames.csv", getppid()).string(), "x");
  const fs::path mine = dir.write(temporary_of("frames.csv", getpid()).string(), "x");
  const fs::path unrelated = dir.write("notes.1234.tmp", "x");

  testing::internal::CaptureStderr();
  write_text_file(dir.path() / "summary.txt", "done\n");
  const std::string err = testing::internal::GetCapturedStderr();

  EXPECT_FALSE(fs::exists(orphan));
  EXPECT_EQ(err, "sphys: note: removed " + orphan.string() + ", a temporary file of process " +
                     std::to_string(ended) + ", which has ended\n");
  EXPECT_TRUE(fs::exists(running));
  EXPECT_TRUE(fs::exists(mine));
  EXPECT_TRUE(fs::exists(unrelated));
  EXPECT_EQ(test::read_whole(dir.path() / "summary.txt"), "done\n");
}

TEST(FileWriteBuffer, KeepsTheSystemsReasonOfAFailedWrite) {
  const int fd = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
  ASSERT_GE(fd, 0) << "no /dev/full";
  FileWriteBuffer buffer(fd);
  std::ostream out(&buffer);
  out << std::string(200'000, 'x');
  EXPECT_FALSE(out);
  EXPECT_EQ(buffer.error(), ENOSPC);
  EXPECT_FALSE(buffer.close());
  EXPECT_EQ(buffer.error(), ENOSPC);
}

TEST(FileWriteBuffer, SeeksBackToPatchAHeader) {
  const test::TempDir dir;
  const fs::path path = dir.path() / "patched";
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  ASSERT_GE(fd, 0);
  FileWriteBuffer buffer(fd);
  std::ostream out(&buffer);
  out << "0000 body";
  out.seekp(0);
  out << "1234";
  EXPECT_TRUE(buffer.close());
  EXPECT_EQ(test::read_whole(path), "1234 body");
}

TEST(AtomicFileErrors, ACreateThatFailsSaysWhy) {
  const test::TempDir dir;
  const fs::path blocked = dir.write("blocked", "a file, not a folder");
  try {
    write_text_file(blocked / "out.txt", "x");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()), (blocked / "out.txt").string() +
                                             ": cannot create a file in its directory: Not a "
                                             "directory");
  }
}

}  // namespace
}  // namespace sphys::tools
