#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "sphys/error.h"
#include "sphys/tools/interrupt.h"
#include "sphys/version.h"
#include "standard_output.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

// An error that follows Ctrl-C is most likely its echo (gnuplot, in the same process group, was
// interrupted too), so it reads as the interruption.
int report_interruption(const sphys::tools::Interrupted& interrupted) {
  std::cerr << "sphys: " << interrupted.what() << '\n';
  return interrupted.exit_code();
}

// "sphys simulate", the command that was running; "sphys" before one was chosen.
std::string running_command(const CLI::App& app) {
  const std::vector<CLI::App*> commands = app.get_subcommands();
  return commands.empty() ? "sphys" : "sphys " + commands.front()->get_name();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sphys: rigid-body collision handling with sphere-trees", "sphys"};
  // At most one command; none is reported after parsing so that an unknown word is named.
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", "sphys " SPHYS_VERSION_STRING);
  sphys::cli::add_mesh_info_command(app);
  sphys::cli::add_build_tree_command(app);
  sphys::cli::add_tree_info_command(app);
  sphys::cli::add_simulate_command(app);
  sphys::cli::add_experiment_command(app);
  sphys::cli::add_export_command(app);
  sphys::cli::add_view_command(app);
  sphys::cli::add_spherize_command(app);
  sphys::cli::add_cache_command(app);
  sphys::cli::add_query_command(app);

  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::cerr << "sphys: error: no command given\n" << app.help();
      return kBadInput;
    }
    sphys::cli::finish_output();
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" that succeed: CLI11 prints them.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::cerr << "sphys: error: " << e.what() << '\n';
    return kBadInput;
  } catch (const sphys::tools::Interrupted& e) {
    return report_interruption(e);
  } catch (const sphys::Error& e) {
    if (const int signal = sphys::tools::interruption_signal()) {
      return report_interruption(sphys::tools::Interrupted(signal));
    }
    std::cerr << "sphys: error: " << e.what() << '\n';
    return kBadInput;
  } catch (const std::bad_alloc&) {
    // Never bad input, whichever file was being read when memory ran out.
    std::cerr << "sphys: internal error: out of memory while running " << running_command(app)
              << '\n';
    return kInternalError;
  } catch (const std::exception& e) {
    if (const int signal = sphys::tools::interruption_signal()) {
      return report_interruption(sphys::tools::Interrupted(signal));
    }
    std::cerr << "sphys: internal error: " << e.what() << '\n';
    return kInternalError;
  }
  return 0;
}
