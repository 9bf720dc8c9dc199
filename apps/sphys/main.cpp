#include <exception>
#include <iostream>

#include "commands.h"
#include "sphys/error.h"
#include "sphys/tools/interrupt.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

// An error that follows Ctrl-C is most likely its echo (gnuplot, in the same process group, was
// interrupted too), so it reads as the interruption.
int report_interruption(const sphys::tools::Interrupted& interrupted) {
  std::cerr << "sphys: " << interrupted.what() << '\n';
  return interrupted.exit_code();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sphys: rigid-body collision handling with sphere-trees", "sphys"};
  // At most one command; none is reported after parsing so that an unknown word is named.
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", "sphys 0.1.0");
  sphys::cli::add_mesh_info_command(app);
  sphys::cli::add_build_tree_command(app);
  sphys::cli::add_tree_info_command(app);
  sphys::cli::add_simulate_command(app);
  sphys::cli::add_experiment_command(app);
  sphys::cli::add_export_command(app);
  sphys::cli::add_view_command(app);
  sphys::cli::add_spherize_command(app);

  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {
      std::cerr << "sphys: error: no command given\n" << app.help();
      return kBadInput;
    }
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
  } catch (const std::exception& e) {
    if (const int signal = sphys::tools::interruption_signal()) {
      return report_interruption(sphys::tools::Interrupted(signal));
    }
    std::cerr << "sphys: internal error: " << e.what() << '\n';
    return kInternalError;
  }
  return 0;
}
