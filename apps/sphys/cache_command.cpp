#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "sphys/error.h"
#include "sphys/tools/tree_cache.h"
#include "standard_output.h"

namespace sphys::cli {
namespace {

struct CacheOptions {
  bool list = false;
  bool verify = false;
  bool clear = false;
};

// "<name>  <bytes> bytes  <what it holds>", or the entry's problem.
std::string entry_line(const tools::CacheEntryCheck& entry) {
  std::string line = entry.path.filename().string() + "  ";
  if (entry.problem) return line + "damaged: " + *entry.problem + "\n";
  return line + std::to_string(entry.bytes) + " bytes  " + entry.description + "\n";
}

void list(const std::filesystem::path& dir) {
  const std::vector<tools::CacheEntryCheck> entries = tools::check_cache(dir);
  std::string text;
  for (const tools::CacheEntryCheck& entry : entries) text += entry_line(entry);
  text += std::to_string(entries.size()) + " entries in " + dir.string() + "\n";
  print_output(text);
}

// Damaged entries are named, and make the command fail: the cache would rebuild them.
void verify(const std::filesystem::path& dir) {
  const std::vector<tools::CacheEntryCheck> entries = tools::check_cache(dir);
  std::size_t damaged = 0;
  std::string text;
  for (const tools::CacheEntryCheck& entry : entries) {
    if (!entry.problem) continue;
    ++damaged;
    text += entry_line(entry);
  }
  print_output(text + std::to_string(entries.size() - damaged) + " of " +
               std::to_string(entries.size()) + " entries in " + dir.string() + " are whole\n");
  if (damaged != 0) {
    throw Error(dir.string() + ": " + std::to_string(damaged) +
                " damaged cache entries (rebuilt when next needed; sphys cache --clear removes "
                "them)");
  }
}

void run(const CacheOptions& options) {
  if (options.list + options.verify + options.clear != 1) {
    throw Error("cache: give one of --list, --verify or --clear");
  }
  const std::filesystem::path dir = tools::default_cache_dir();
  if (options.list) return list(dir);
  if (options.verify) return verify(dir);
  const std::size_t removed = tools::clear_cache(dir);
  print_output("removed " + std::to_string(removed) + " entries from " + dir.string() + "\n");
}

}  // namespace

void add_cache_command(CLI::App& app) {
  auto options = std::make_shared<CacheOptions>();
  CLI::App* cmd =
      app.add_subcommand("cache",
                         "Show, check or empty the sphere-tree cache ($SPHYS_CACHE_DIR, else "
                         "$XDG_CACHE_HOME/sphys, else ~/.cache/sphys)");
  cmd->add_flag("--list", options->list, "Show every entry: its size and what it holds");
  cmd->add_flag("--verify", options->verify,
                "Check every entry (checksum, origin, tree); fails naming the damaged ones");
  cmd->add_flag("--clear", options->clear,
                "Remove every entry, and temporary files of ended processes");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
