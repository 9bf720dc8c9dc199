#include <array>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <optional>
#include <random>
#include <span>
#include <spawn.h>
#include <string>
#include <string_view>
#include <sys/wait.h>
#include <system_error>
#include <unistd.h>
#include <utility>
#include <vector>

#include "sphys/error.h"
#include "sphys/tools/experiment.h"

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

// "<path>.<random hex><suffix>": a scratch name next to `path` (so that a rename stays within one
// file system) that runs sharing a directory do not both pick.
fs::path tagged(const fs::path& path, std::string_view suffix) {
  std::random_device random;
  const std::uint64_t tag = (std::uint64_t{random()} << 32) ^ random();
  std::array<char, 17> hex{};
  const auto result = std::to_chars(hex.data(), hex.data() + hex.size(), tag, 16);
  fs::path name = path;
  name += ".";
  name += std::string_view(hex.data(), static_cast<std::size_t>(result.ptr - hex.data()));
  name += suffix;
  return name;
}

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

std::ofstream open_scratch(const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error::in_file(path, "cannot create a file in the plot directory");
  return out;
}

// One block per row, "frame step_ms contacts" per line; gnuplot's `index` picks a block, blocks
// being separated by two blank lines.
void write_data(const fs::path& path, const std::vector<const RowResult*>& rows) {
  std::ofstream out = open_scratch(path);
  for (const RowResult* result : rows) {
    for (std::size_t i = 0; i < result->frames.size(); ++i) {
      const FrameSample& frame = result->frames[i];
      out << i + 1 << ' ' << number(frame.step_ms) << ' ' << frame.contacts << '\n';
    }
    out << "\n\n";
  }
  out.close();
  if (!out) throw Error::in_file(path, "cannot write the plot data (is the disk full?)");
}

struct Drawing {
  const RowResult* result;
  fs::path frame_time_png;  // temporary names until gnuplot has finished
  fs::path contacts_png;
};

void write_script(const fs::path& path, const fs::path& data,
                  const std::vector<Drawing>& drawings) {
  std::ofstream out = open_scratch(path);
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
  out.close();
  if (!out) throw Error::in_file(path, "cannot write the gnuplot script (is the disk full?)");
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
    throw Error("gnuplot could not be started (" + program +
                "): " + std::generic_category().message(spawn_error));
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

void create_plot_directory(const fs::path& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw Error::in_file(directory, "cannot create the plot directory: " + ec.message());
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
  const fs::path data = scratch.add(tagged(base, ".dat"));
  const fs::path script = scratch.add(tagged(base, ".gp"));
  const fs::path log = scratch.add(tagged(base, ".log"));

  std::vector<Drawing> drawings;
  std::vector<std::pair<fs::path, fs::path>> renames;  // temporary name, final name
  const auto staged = [&](const std::string& name) {
    const fs::path target = directory / name;
    fs::path temporary = scratch.add(tagged(target, ".tmp"));
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

  std::vector<fs::path> written;
  for (const auto& [temporary, target] : renames) {
    std::error_code ec;
    if (fs::file_size(temporary, ec) == 0 || ec) {
      throw Error::in_file(target, "gnuplot finished without drawing the plot");
    }
    fs::rename(temporary, target, ec);
    if (ec) throw Error::in_file(target, "cannot replace the file: " + ec.message());
    written.push_back(target);
  }
  return written;
}

}  // namespace sphys::tools
