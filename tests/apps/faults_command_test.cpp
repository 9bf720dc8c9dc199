// Faults of the environment, put in on purpose as a user would meet them: a damaged sphere-tree
// cache entry, an unreadable cache folder, a full device or file system, too few file
// descriptors, too little memory, a killed run's temporary file. None may give a wrong result or
// a false success (docs/reliability.md, "Faults").

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <sys/mount.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "apps/cli.h"
#include "support/sanitized_run.h"
#include "support/temp_file.h"

namespace sphys {
namespace {

namespace fs = std::filesystem;
using test::sphys_cli;
using test::sphys_cli_after;
using testing::HasSubstr;

// A cache folder of the test's own, so that damaging an entry touches no other test.
fs::path own_cache(const test::TempDir& dir) {
  const fs::path cache = dir.path() / "cache";
  setenv("SPHYS_CACHE_DIR", cache.c_str(), 1);
  return cache;
}

// The one entry a run left in the cache folder.
fs::path only_entry(const fs::path& cache) {
  const std::vector<fs::path> files = test::files_in(cache);
  EXPECT_EQ(files.size(), 1u);
  return files.empty() ? fs::path() : files.front();
}

void overwrite(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

std::vector<std::string> quick_run(const fs::path& out, int frames) {
  return {"simulate", "stacks:1x1",           "--depth", "1",         "--ground", "plane",
          "--frames", std::to_string(frames), "--out",   out.string()};
}

// The case: one leaf radius of the cached tree changed by a digit.
TEST(Faults, SimulateRebuildsADamagedCacheEntryAndMovesAsACleanRun) {
  const test::TempDir dir;
  const fs::path cache = own_cache(dir);
  const std::vector<std::string> run = {"simulate", "stacks:1x2", "--depth", "2", "--frames", "40"};
  std::vector<std::string> clean_run = run;
  clean_run.insert(clean_run.end(), {"--out", (dir.path() / "clean").string()});
  ASSERT_EQ(sphys_cli(clean_run).exit_code, 0);
  const fs::path entry = only_entry(cache);
  const std::string clean_entry = test::read_whole(entry);

  std::string damaged = clean_entry;
  // The last line, a leaf, ends "<radius> 1\n": its radius's first decimal changes (0.12 -> 0.22).
  const std::size_t radius = damaged.rfind(' ', damaged.size() - 4) + 1;
  ASSERT_EQ(damaged.compare(radius, 2, "0."), 0) << damaged.substr(radius);
  damaged[radius + 2] = damaged[radius + 2] == '1' ? '2' : '1';
  overwrite(entry, damaged);

  std::vector<std::string> again = run;
  again.insert(again.end(), {"--out", (dir.path() / "again").string()});
  const test::CommandResult r = sphys_cli(again);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("sphys: note: " + entry.string() +
                               ": a damaged sphere-tree cache entry (its checksum does not match "
                               "its bytes (changed or cut short)); rebuilding and replacing it\n"));
  EXPECT_EQ(test::read_whole(dir.path() / "again" / "recording.sphysrec"),
            test::read_whole(dir.path() / "clean" / "recording.sphysrec"));
  EXPECT_EQ(test::read_whole(entry), clean_entry);
  unsetenv("SPHYS_CACHE_DIR");
}

// The case: build-tree said "loaded from the cache" and wrote the damaged tree to -o.
TEST(Faults, BuildTreeNeverCopiesADamagedEntry) {
  const test::TempDir dir;
  const fs::path cache = own_cache(dir);
  const std::string clean = (dir.path() / "clean.sph").string();
  const std::string again = (dir.path() / "again.sph").string();
  ASSERT_EQ(sphys_cli({"build-tree", "bunny", "--method", "octree", "--depth", "3", "-o", clean})
                .exit_code,
            0);
  const fs::path entry = only_entry(cache);
  std::string bytes = test::read_whole(entry);
  // The first line of the tree's .sph text, "3 8" (depth 3, branching 8): the entry's first line
  // or one after its header.
  const std::size_t header = ("\n" + bytes).find("\n3 8\n");
  ASSERT_NE(header, std::string::npos);
  bytes[header] = '2';
  overwrite(entry, bytes);

  const test::CommandResult r =
      sphys_cli({"build-tree", "bunny", "--method", "octree", "--depth", "3", "-o", again});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("built in"));
  EXPECT_THAT(r.err, HasSubstr(entry.string() + ": a damaged sphere-tree cache entry"));
  EXPECT_EQ(test::read_whole(again), test::read_whole(clean));
  unsetenv("SPHYS_CACHE_DIR");
}

TEST(Faults, CacheCommandListsVerifiesAndClears) {
  const test::TempDir dir;
  const fs::path cache = own_cache(dir);
  const std::string tree = (dir.path() / "t.sph").string();
  ASSERT_EQ(sphys_cli({"build-tree", "bunny", "--method", "octree", "--depth", "2", "-o", tree})
                .exit_code,
            0);
  const fs::path entry = only_entry(cache);
  const test::CommandResult listed = sphys_cli({"cache", "--list"});
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_THAT(listed.out, HasSubstr(entry.filename().string() + "  "));
  EXPECT_THAT(listed.out, HasSubstr(" bytes  octree, branching 8, depth 2 ("));
  EXPECT_THAT(listed.out, HasSubstr("1 entries in " + cache.string() + "\n"));
  EXPECT_EQ(sphys_cli({"cache", "--verify"}).exit_code, 0);

  std::string bytes = test::read_whole(entry);
  bytes.resize(bytes.size() - 2);  // cut inside the last radius's line
  overwrite(entry, bytes);
  const test::CommandResult verified = sphys_cli({"cache", "--verify"});
  EXPECT_EQ(verified.exit_code, 2);
  EXPECT_THAT(verified.out, HasSubstr(entry.filename().string() + "  damaged: its checksum"));
  EXPECT_EQ(verified.err, "sphys: error: " + cache.string() +
                              ": 1 damaged cache entries (rebuilt when next needed; sphys cache "
                              "--clear removes them)\n");

  const test::CommandResult cleared = sphys_cli({"cache", "--clear"});
  EXPECT_EQ(cleared.exit_code, 0) << cleared.err;
  EXPECT_EQ(cleared.out, "removed 1 entries from " + cache.string() + "\n");
  EXPECT_FALSE(fs::exists(entry));
  EXPECT_EQ(sphys_cli({"cache"}).exit_code, 2);
  unsetenv("SPHYS_CACHE_DIR");
}

// Four processes building the same tree into one empty cache: each entry is written to its own
// temporary file and renamed into place, so none reads half an entry or another's damage.
TEST(Faults, FourProcessesSharingACacheGetTheSameTree) {
  const test::TempDir dir;
  const fs::path cache = own_cache(dir);
  std::vector<std::unique_ptr<test::RunningCommand>> runs;
  for (int i = 0; i < 4; ++i) {
    const std::string tree = (dir.path() / (std::to_string(i) + ".sph")).string();
    runs.push_back(std::make_unique<test::RunningCommand>(
        SPHYS_CLI_PATH, std::vector<std::string>{"build-tree", "bunny", "--method", "octree",
                                                 "--depth", "3", "-o", tree}));
  }
  for (auto& run : runs) {
    const test::CommandResult r = run->wait();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
  }
  const std::string first = test::read_whole(dir.path() / "0.sph");
  EXPECT_FALSE(first.empty());
  for (int i = 1; i < 4; ++i) {
    EXPECT_EQ(test::read_whole(dir.path() / (std::to_string(i) + ".sph")), first);
  }
  (void)only_entry(cache);
  EXPECT_TRUE(test::temporary_files_in(cache).empty());
  EXPECT_EQ(sphys_cli({"cache", "--verify"}).exit_code, 0);
  unsetenv("SPHYS_CACHE_DIR");
}

// Was `internal error: filesystem error: status: Permission denied`, exit 1. Root reads a folder
// of mode 000 all the same, so as root the command runs as the user nobody.
TEST(Faults, UnreadableCacheFolderIsSkippedWithOneNote) {
  const bool root = geteuid() == 0;
  const std::vector<std::string> as_nobody = {"--reuid=65534", "--regid=65534", "--clear-groups",
                                              SPHYS_CLI_PATH};
  if (root) {
    if (::access("/usr/bin/setpriv", X_OK) != 0) {
      GTEST_SKIP() << "running as root without setpriv to drop the privilege: a folder of mode "
                      "000 stays readable";
    }
    std::vector<std::string> version = as_nobody;
    version.push_back("--version");
    if (test::run_command("/usr/bin/setpriv", version).exit_code != 0) {
      GTEST_SKIP() << "the user nobody cannot run " << SPHYS_CLI_PATH;
    }
  }
  const test::TempDir dir;
  const fs::path cache = dir.path() / "cache";
  const fs::path out = dir.path() / "out";
  fs::create_directories(cache);
  fs::create_directories(out);
  fs::permissions(cache, fs::perms::none);
  fs::permissions(out, fs::perms::all);
  std::vector<std::string> args = quick_run(out, 5);
  if (root) args.insert(args.begin(), as_nobody.begin(), as_nobody.end());
  setenv("SPHYS_CACHE_DIR", cache.c_str(), 1);
  const test::CommandResult r =
      root ? test::run_command("/usr/bin/setpriv", args) : sphys_cli(args);
  unsetenv("SPHYS_CACHE_DIR");
  fs::permissions(cache, fs::perms::owner_all);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "sphys: note: the sphere-tree cache " + cache.string() +
                       " cannot be used (Permission denied); going on without it\n");
  EXPECT_TRUE(fs::exists(out / "recording.sphysrec"));
}

// Was exit 0 with nothing written and nothing said.
TEST(Faults, StandardOutputOnAFullDeviceFails) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  std::vector<std::string> json_run = quick_run(dir.path(), 2);
  json_run.push_back("--json");
  const test::CommandResult simulate = sphys_cli_after("exec >/dev/full", json_run);
  EXPECT_EQ(simulate.exit_code, 2);
  EXPECT_EQ(simulate.err, "sphys: error: standard output: cannot write: No space left on device\n");

  // A report printed with printf, flushed when the command ends.
  const test::CommandResult built =
      sphys_cli_after("exec >/dev/full", {"build-tree", "bunny", "--method", "octree", "--depth",
                                          "1", "-o", (dir.path() / "t.sph").string()});
  EXPECT_EQ(built.exit_code, 2);
  EXPECT_EQ(built.err, "sphys: error: standard output: cannot write: No space left on device\n");
}

// A file system that fills up, as RLIMIT_FSIZE makes one for this process alone: a write past
// the limit fails with EFBIG once SIGXFSZ is ignored. The earlier run's outputs stay whole.
TEST(Faults, OutputOnAFullFileSystemFailsAndKeepsTheEarlierRun) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  ASSERT_EQ(sphys_cli(quick_run(dir.path(), 5)).exit_code, 0);
  const std::string csv = test::read_whole(dir.path() / "frames.csv");
  const std::string recording = test::read_whole(dir.path() / "recording.sphysrec");

  // 64 blocks (of 512 or 1024 bytes): the recording of 5,000 frames is 140 kB.
  const test::CommandResult r =
      sphys_cli_after("ulimit -f 64\ntrap '' XFSZ", quick_run(dir.path(), 5000));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "sphys: error: " + (dir.path() / "recording.sphysrec").string() +
                       ": cannot write the file: File too large\n");
  EXPECT_TRUE(test::temporary_files_in(dir.path()).empty());
  EXPECT_EQ(test::read_whole(dir.path() / "frames.csv"), csv);
  EXPECT_EQ(test::read_whole(dir.path() / "recording.sphysrec"), recording);
}

// A real file system that fills up: a 96 kB tmpfs mounted for the test, where it may mount one
// (as root), unmounted when done.
class SmallTmpfs {
 public:
  explicit SmallTmpfs(const fs::path& at) : at_(at) {
    fs::create_directories(at);
    mounted_ = ::mount("tmpfs", at.c_str(), "tmpfs", 0, "size=96k") == 0;
  }
  ~SmallTmpfs() {
    if (mounted_) ::umount2(at_.c_str(), MNT_DETACH);
  }
  SmallTmpfs(const SmallTmpfs&) = delete;
  SmallTmpfs& operator=(const SmallTmpfs&) = delete;
  [[nodiscard]] bool mounted() const { return mounted_; }

 private:
  fs::path at_;
  bool mounted_ = false;
};

// The run of 5,000 frames needs more than the 96 kB there are (its CSV and recording): the
// system's own reason is given, no temporary file is left, and the earlier run's outputs stay.
TEST(Faults, OutputOnAFullTmpfsSaysNoSpaceAndKeepsTheEarlierRun) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "small";
  const SmallTmpfs disk(out);
  if (!disk.mounted()) {
    GTEST_SKIP() << "cannot mount a tmpfs here (it takes root); "
                    "OutputOnAFullFileSystemFailsAndKeepsTheEarlierRun fills a file-size limit";
  }
  ASSERT_EQ(sphys_cli(quick_run(out, 5)).exit_code, 0);
  const std::string csv = test::read_whole(out / "frames.csv");
  const std::string recording = test::read_whole(out / "recording.sphysrec");

  const test::CommandResult r = sphys_cli(quick_run(out, 5000));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("sphys: error: " + out.string() + "/"));
  EXPECT_THAT(r.err, HasSubstr(": No space left on device\n"));
  EXPECT_TRUE(test::temporary_files_in(out).empty());
  EXPECT_EQ(test::read_whole(out / "frames.csv"), csv);
  EXPECT_EQ(test::read_whole(out / "recording.sphysrec"), recording);
}

// Was exit 0 with a PNG cut at 16 kB: gnuplot does not report its failed writes. 12 blocks (6 kB
// in dash's 512-byte blocks, 12 kB in bash's 1024) let the report and the CSV through (2.4 kB at
// most) but neither PNG (15 and 23 kB).
TEST(Faults, PlotOnAFullFileSystemFails) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const fs::path out = dir.path() / "experiment";
  const test::CommandResult r = sphys_cli_after(
      "ulimit -f 12\ntrap '' XFSZ",
      {"experiment", "--only", "d2-8x10", "--frames", "3", "--no-pictures", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::MatchesRegex("sphys: error: .*\\.png: cannot write the file: File "
                                           "too large \\(gnuplot stopped at [0-9]+ bytes\\)\n"));
  for (const fs::path& file : test::files_in(out)) {
    EXPECT_NE(file.extension(), ".png") << file;
  }
  EXPECT_TRUE(test::temporary_files_in(out).empty());
}

// Was "cannot create a file in its directory", the system's reason dropped.
TEST(Faults, TooFewFileDescriptorsSayWhy) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult r = sphys_cli_after("ulimit -n 4", quick_run(dir.path(), 5));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, testing::MatchesRegex("sphys: error: .*: Too many open files\n"));
  EXPECT_TRUE(test::temporary_files_in(dir.path()).empty());
}

// Was exit 2 blaming the valid bunny.obj (`/bodies/0: …/bunny.obj: std::bad_alloc`).
TEST(Faults, OutOfMemoryIsAnInternalErrorBlamingNoFile) {
  if (test::sanitized_run()) GTEST_SKIP() << "AddressSanitizer reserves far more than 50 MB";
  test::use_shared_tree_cache();
  const test::TempDir dir;
  const test::CommandResult r =
      sphys_cli_after("ulimit -v 51200",
                      {"simulate", "stacks:500x10", "--frames", "1", "--out", dir.path().string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sphys: internal error: out of memory while running sphys simulate\n");
}

// A SIGKILL leaves the recording's temporary file; the next run into the folder removes it.
TEST(Faults, AKilledRunsTemporaryFileIsRemovedByTheNextRun) {
  test::use_shared_tree_cache();
  const test::TempDir dir;
  pid_t killed = 0;
  {
    test::RunningCommand command(SPHYS_CLI_PATH, quick_run(dir.path(), 1'000'000));
    const auto start = std::chrono::steady_clock::now();
    while (test::temporary_files_in(dir.path()).empty() &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(30)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    killed = command.pid();
    kill(killed, SIGKILL);
    EXPECT_EQ(command.wait().exit_code, 128 + SIGKILL);
  }
  const std::vector<fs::path> left = test::temporary_files_in(dir.path());
  ASSERT_EQ(left.size(), 1u) << "the run never started recording";
  EXPECT_THAT(left.front().filename().string(),
              HasSubstr(".sphys-" + std::to_string(killed) + "-"));

  const test::CommandResult r = sphys_cli(quick_run(dir.path(), 5));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "sphys: note: removed " + left.front().string() +
                       ", a temporary file of process " + std::to_string(killed) +
                       ", which has ended\n");
  EXPECT_TRUE(test::temporary_files_in(dir.path()).empty());
}

}  // namespace
}  // namespace sphys
