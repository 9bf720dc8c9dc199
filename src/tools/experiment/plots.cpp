#include <array>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <optional>
#include <span>
#include <spawn.h>
#include <sstream>
#include <string>
#include <string_view>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>
#include <utility>
#include <vector>

#include "io/temporary_files.h"
#include "sphys/error.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/system_reason.h"
#include "sphys/tools/text_file.h"

extern char** environ;

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Files that must not outlive one call of write_plots: the data, the script, gnuplot's messages,
// and PNGs still under their temporary names when something failed.
class ScratchFiles {
 public:
  ScratchFiles() = default;
  ~ScratchFiles() {
    for (const fs::path& path : paths_) {
      std::error_code ignored;
      fs::remove(path, ignored);
    }
  }
  ScratchFiles(const ScratchFiles&) = delete;
  ScratchFiles& operator=(const ScratchFiles&) = delete;

  fs::path add(fs::path path) { return paths_.emplace_back(std::move(path)); }

 private:
  std::vector<fs::path> paths_;
};

// The program as found on PATH (an empty entry is the current directory), or nothing.
std::optional<fs::path> find_on_path(std::string_view program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::string_view entries(path);
  while (true) {
    const std::size_t colon = entries.find(':');
    const std::string_view entry = entries.substr(0, colon);
    const fs::path candidate = fs::path(entry.empty() ? "." : entry) / program;
    std::error_code ec;
    if (::access(candidate.c_str(), X_OK) == 0 && !fs::is_directory(candidate, ec)) {
      return candidate;
    }
    if (colon == std::string_view::npos) return std::nullopt;
    entries.remove_prefix(colon + 1);
  }
}

fs::path gnuplot_path() {
  std::optional<fs::path> found = find_on_path("gnuplot");
  if (!found) throw Error("gnuplot not found; install gnuplot-nox (scripts/setup does)");
  return *found;
}

// A gnuplot string literal. In single quotes gnuplot interprets nothing but '' (one quote); a
// line break cannot be written at all.
std::string quoted(const fs::path& path) {
  const std::string text = path.string();
  if (text.find_first_of("\r\n") != std::string::npos) {
    throw Error::in_file(path, "gnuplot cannot take a file name with a line break");
  }
  std::string literal = "'";
  for (const char c : text) {
    if (c == '\'') literal += '\'';
    literal += c;
  }
  return literal + "'";
}

// Shortest text that reads back as the same double, independent of the locale.
std::string number(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

// One block per row, "frame step_ms contacts" per line; gnuplot's `index` picks a block, blocks
// being separated by two blank lines.
void write_data(const fs::path& path, const std::vector<const RowResult*>& rows) {
  std::string text;
  for (const RowResult* result : rows) {
    for (std::size_t i = 0; i < result->frames.size(); ++i) {
      const FrameSample& frame = result->frames[i];
      text += std::to_string(i + 1) + ' ' + number(frame.step_ms) + ' ' +
              std::to_string(frame.contacts) + '\n';
    }
    text += "\n\n";
  }
  write_text_file(path, text);
}

struct Drawing {
  const RowResult* result;
  fs::path frame_time_png;  // temporary names until gnuplot has finished
  fs::path contacts_png;
};

void write_script(const fs::path& path, const fs::path& data,
                  const std::vector<Drawing>& drawings) {
  std::ostringstream out;
  // noenhanced: titles are printed as written, with no markup in underscores or carets.
  out << "set terminal pngcairo size 960,540 noenhanced\n"
         "set grid\n"
         "set key off\n"
         "set xlabel 'frame'\n"
         "set yrange [0:*]\n";
  for (std::size_t i = 0; i < drawings.size(); ++i) {
    const std::string id = drawings[i].result->row.id();
    out << "set output " << quoted(drawings[i].frame_time_png) << "\n"
        << "set title '" << id << ": frame time (physics step, no rendering)'\n"
        << "set ylabel 'frame time (ms)'\n"
        << "plot " << quoted(data) << " index " << i << " using 1:2 with lines\n"
        << "set output " << quoted(drawings[i].contacts_png) << "\n"
        << "set title '" << id << ": contacts per frame'\n"
        << "set ylabel 'contacts'\n"
        << "plot " << quoted(data) << " index " << i << " using 1:3 with lines\n";
  }
  // Closes the last PNG.
  out << "unset output\n";
  write_text_file(path, out.str());
}

// A scratch file's bytes (a PNG of a few tens of kilobytes); empty if it cannot be read.
std::string read_whole_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The errno of appending a block to the file, 0 if that succeeds.
int append_error(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) return errno;
  static const std::array<char, 1 << 16> kBlock{};
  const int error = ::write(fd, kBlock.data(), kBlock.size()) < 0 ? errno : 0;
  ::close(fd);
  return error;
}

// The last line gnuplot printed that says something: where its script went wrong.
std::string last_message(const fs::path& log) {
  std::ifstream in(log, std::ios::binary);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r^") != std::string::npos) last = line;
  }
  if (!last.empty() && last.back() == '\r') last.pop_back();
  return last.empty() ? "no message" : last;
}

// Runs gnuplot on the script without a shell, so that no file name is ever parsed as a command.
void run_gnuplot(const fs::path& gnuplot, const fs::path& script, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  std::string program = gnuplot.string();
  std::string script_argument = script.string();
  std::array<char*, 3> argv = {program.data(), script_argument.data(), nullptr};
  pid_t pid = 0;
  const int spawn_error =
      posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) {
    throw Error("gnuplot could not be started (" + program + "): " + system_reason(spawn_error));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("gnuplot: lost track of the process");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  const std::string how = WIFEXITED(status)
                              ? "exited with status " + std::to_string(WEXITSTATUS(status))
                              : "was killed by signal " + std::to_string(WTERMSIG(status));
  throw Error("gnuplot " + how + ": " + last_message(log));
}

// gnuplot exits 0 even when it could not write its PNG (a full disk leaves it cut short), so each
// PNG is checked for its end chunk. The system's reason is found by trying to write there once
// more: the same write fails the same way.
void check_whole_png(const fs::path& png, const fs::path& target) {
  // The last 12 bytes of every PNG: IEND's zero length, its type and its CRC.
  static constexpr std::string_view kEnd("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  std::error_code ec;
  if (!fs::exists(png, ec))
    throw Error::in_file(target, "gnuplot finished without drawing the plot");
  const std::string bytes = read_whole_file(png);
  if (bytes.ends_with(kEnd)) return;
  const std::string cut = "gnuplot stopped at " + std::to_string(bytes.size()) + " bytes";
  if (const int reason = append_error(png)) {
    throw Error::in_file(target,
                         "cannot write the file: " + system_reason(reason) + " (" + cut + ")");
  }
  throw Error::in_file(target, "gnuplot did not draw the whole plot (" + cut + ", no PNG end)");
}

void create_plot_directory(const fs::path& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) {
    throw Error::in_file(directory,
                         "cannot create the plot directory: " + system_reason(ec.value()));
  }
}

}  // namespace

bool plots_available() { return find_on_path("gnuplot").has_value(); }

// Two PNGs per row rather than one with two panels: each reads alone at full size in the report.
PlotFiles plot_files(const ExperimentRow& row) {
  const std::string id = row.id();
  return {id + "-frame-time.png", id + "-contacts.png"};
}

std::vector<fs::path> write_plots(const fs::path& directory, std::span<const RowResult> results) {
  std::vector<const RowResult*> rows;
  for (const RowResult& result : results) {
    if (!result.frames.empty()) rows.push_back(&result);  // nothing to draw otherwise
  }
  if (rows.empty()) return {};
  const fs::path gnuplot = gnuplot_path();
  create_plot_directory(directory);

  // Absolute, so that the script's path cannot be taken for one of gnuplot's options.
  const fs::path base = fs::absolute(directory) / ".plots";
  ScratchFiles scratch;
  remove_orphaned_temporaries(directory);
  const fs::path data = scratch.add(temporary_sibling(base.string() + "-data"));
  const fs::path script = scratch.add(temporary_sibling(base.string() + "-script"));
  const fs::path log = scratch.add(temporary_sibling(base.string() + "-log"));

  std::vector<Drawing> drawings;
  std::vector<std::pair<fs::path, fs::path>> renames;  // temporary name, final name
  const auto staged = [&](const std::string& name) {
    const fs::path target = directory / name;
    fs::path temporary = scratch.add(temporary_sibling(target));
    renames.emplace_back(temporary, target);
    return temporary;
  };
  for (const RowResult* result : rows) {
    const PlotFiles files = plot_files(result->row);
    drawings.push_back({result, staged(files.frame_time), staged(files.contacts)});
  }

  write_data(data, rows);
  write_script(script, data, drawings);
  run_gnuplot(gnuplot, script, log);

  // Every plot checked before any replaces an earlier run's.
  for (const auto& [temporary, target] : renames) check_whole_png(temporary, target);
  std::vector<fs::path> written;
  for (const auto& [temporary, target] : renames) {
    std::error_code ec;
    fs::rename(temporary, target, ec);
    if (ec) throw Error::in_file(target, "cannot replace the file: " + system_reason(ec.value()));
    written.push_back(target);
  }
  return written;
}

}  // namespace sphys::tools
