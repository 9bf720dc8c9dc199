#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress.h"
#include "sphys/error.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/experiment_json.h"
#include "sphys/tools/interrupt.h"
#include "sphys/tools/machine.h"
#include "sphys/tools/run_experiment.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/text_file.h"
#include "sphys/tools/tree_cache.h"
#include "standard_output.h"
#include "viewer/frame_drawer.h"
#include "viewer/window.h"

namespace sphys::cli {
namespace {

namespace fs = std::filesystem;

struct ExperimentCommandOptions {
  int frames = 880;
  std::optional<std::string> only;
  std::string out = "out/experiment";
  std::string ground = "octree";
  // ExperimentMode's defaults: the paper's response.
  std::string mode{tools::response_mode_name(tools::ExperimentMode{}.response)};
  std::string contacts{tools::contact_set_name(tools::ExperimentMode{}.contacts)};
  bool json = false;
  bool no_plots = false;
  bool no_cache = false;
  bool no_pictures = false;
  bool render = false;
  bool render_all = false;
};

// Figure 2's pictures of one row (its first and last frame) and, with --render, every
// `drawn_every`-th frame drawn: a frame callback for run_experiment_row. Without an OpenGL window
// (no display) the row says why it has no pictures (--render is refused before any row runs).
class RowPictures {
 public:
  // drawn_every: 0 draws the pictures' frames only.
  RowPictures(const fs::path& out, const tools::ExperimentRow& row, std::uint32_t drawn_every)
      : out_(out), id_(row.id()), drawn_every_(drawn_every) {}

  // Whether it drew the frame.
  bool operator()(const tools::ExperimentFrame& frame) {
    const bool sampled =
        drawn_every_ > 0 && static_cast<std::uint32_t>(frame.frame) % drawn_every_ == 0;
    if (!sampled && frame.frame != 0 && !frame.last) return false;
    if (!drawer_ && missing_.empty()) {
      try {
        drawer_ = std::make_unique<viewer::FrameDrawer>(
            frame.scene, frame.setup, tools::kDrawnFrameWidth, tools::kDrawnFrameHeight);
      } catch (const Error&) {
        throw;
      } catch (const std::runtime_error& error) {
        missing_ = error.what();
      }
    }
    if (!drawer_) return false;
    drawer_->draw(frame.frame == 0);
    if (frame.frame == 0) save(first_, "-first.png");
    // The last picture is saved once the row is over (report()), so that writing it is not timed
    // as drawing.
    return true;
  }

  // Into the row's result: the pictures' file names, or why there are none. Saves the last frame
  // drawn as the last picture.
  void report(tools::RowResult& result) {
    if (drawer_) save(last_, "-last.png");
    result.first_picture = first_;
    result.last_picture = last_;
    result.pictures_missing = missing_;
    result.drawn_every = drawer_ ? drawn_every_ : 0;
  }

 private:
  void save(std::string& name, const char* suffix) {
    name = id_ + suffix;
    drawer_->save(out_ / name);
  }

  fs::path out_;
  std::string id_;
  std::uint32_t drawn_every_;
  std::unique_ptr<viewer::FrameDrawer> drawer_;
  std::string first_;
  std::string last_;
  std::string missing_;
};

// The machine, for reports: the experiment steps one world at a time on one thread.
std::string machine() { return tools::machine_description() + ", one used"; }

void run(const ExperimentCommandOptions& options) {
  tools::catch_interruptions();
  if (options.frames < 1) throw Error("--frames must be at least 1");
  const std::uint32_t drawn_every =
      options.render_all ? 1 : (options.render ? tools::kRenderSampleStride : 0);
  if (drawn_every > 0) {
    try {
      const viewer::Window probe(16, 16, 0, false);
    } catch (const std::runtime_error& error) {
      throw Error(std::string(options.render_all ? "--render-all" : "--render") +
                  ": cannot draw frames: " + error.what() +
                  " (run under xvfb-run where there is no display)");
    }
  }
  std::vector<tools::ExperimentRow> rows;
  if (options.only) {
    rows = tools::parse_rows(*options.only);
  } else {
    for (const tools::PaperRow& paper : tools::paper_table()) rows.push_back(paper.row);
  }
  const tools::GroundSpec::Kind ground = tools::parse_ground_option(options.ground);
  tools::ExperimentOptions experiment;
  experiment.mode.response = parse_option("--mode", options.mode, tools::parse_response_mode);
  experiment.mode.contacts = parse_option("--contacts", options.contacts, tools::parse_contact_set);
  const fs::path out(options.out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error::in_file(out, "cannot create the output folder: " + ec.message());

  experiment.frames = options.frames;
  experiment.ground = ground;

  if (!options.no_cache) experiment.cache_dir = tools::default_cache_dir();
  std::vector<tools::RowResult> results;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ProgressBar bar("row " + std::to_string(i + 1) + "/" + std::to_string(rows.size()) + " " +
                    rows[i].id());
    experiment.progress = [&bar](double fraction) { bar.update(fraction); };
    auto pictures = std::make_shared<RowPictures>(out, rows[i], drawn_every);
    if (!options.no_pictures || drawn_every > 0) {
      experiment.on_frame = [pictures](const tools::ExperimentFrame& frame) {
        return (*pictures)(frame);
      };
    }
    tools::RowResult result = tools::run_experiment_row(rows[i], experiment);
    pictures->report(result);
    results.push_back(std::move(result));
  }

  for (const tools::RowResult& result : results) {
    tools::write_row_csv(out / (result.row.id() + ".csv"), result);
  }
  std::vector<fs::path> plots;
  if (!options.no_plots) plots = tools::write_plots(out, results);
  const fs::path report = out / "report.md";
  tools::write_text_file(report,
                         tools::markdown_report(results, machine(), experiment.mode, plots));

  if (options.json) {
    nlohmann::ordered_json json;
    json["machine"] = machine();
    json["response"] = tools::response_mode_name(experiment.mode.response);
    json["contacts"] = tools::contact_set_name(experiment.mode.contacts);
    json["rows"] = nlohmann::ordered_json::array();
    std::vector<tools::RowSummary> summaries;
    for (const tools::RowResult& result : results) {
      json["rows"].push_back(nlohmann::ordered_json::parse(tools::row_result_json(result)));
      summaries.push_back(tools::summarize(result));
    }
    json["statistics"] =
        nlohmann::ordered_json::parse(tools::statistics_json(tools::compute_statistics(summaries)));
    json["report"] = report.string();
    print_output(json.dump(2) + "\n");
    return;
  }
  std::printf("%s", tools::comparison_text(results, experiment.mode).c_str());
  std::printf("\nmachine: %s\nreport: %s (with the per-frame CSVs%s in %s)\n", machine().c_str(),
              report.string().c_str(), plots.empty() ? "" : " and plots", out.string().c_str());
}

}  // namespace

void add_experiment_command(CLI::App& app) {
  auto options = std::make_shared<ExperimentCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "experiment", "Reproduce the paper's evaluation (Table 1 and the statistics of its §5)");
  cmd->add_option("--frames", options->frames, "Frames per row (the paper ran 880)")
      ->capture_default_str();
  cmd->add_option("--only", options->only,
                  "Comma-separated rows, e.g. d2-4x25,d3-8x10 (default: all eight)");
  cmd->add_option("--out", options->out, "Folder for report.md, the CSVs and the plots")
      ->check(kFileName)
      ->capture_default_str();
  cmd->add_option("--ground", options->ground,
                  "octree: the paper's 5-level octree of a 16 m thin box; plane: the exact plane")
      ->capture_default_str();
  // The experiment's own defaults (tools::ExperimentMode), not the runtime's: shown by CLI11.
  cmd->add_option("--mode", options->mode, std::string(setting_of("response").doc))
      ->capture_default_str();
  cmd->add_option("--contacts", options->contacts, std::string(setting_of("solver.contacts").doc))
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "Print the results as JSON");
  cmd->add_flag("--no-plots", options->no_plots, "Skip the gnuplot PNGs");
  cmd->add_flag("--no-cache", options->no_cache, "Build sphere-trees even if they are cached");
  cmd->add_flag("--no-pictures", options->no_pictures,
                "Skip Figure 2's pictures (each row's first and last frame, drawn offscreen)");
  cmd->add_flag("--render", options->render,
                "Draw every " + std::to_string(tools::kRenderSampleStride) +
                    "th frame offscreen too, so that FPS counts drawing as the paper's did (each "
                    "frame not drawn counted at the drawn ones' mean)");
  cmd->add_flag("--render-all", options->render_all,
                "Draw every frame offscreen too, so that FPS counts drawing as the paper's did");
  cmd->callback([options] { run(*options); });
}

}  // namespace sphys::cli
