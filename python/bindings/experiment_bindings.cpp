// The paper's evaluation: its Table 1 and statistics, rows run headless, our figures beside.

#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/experiment_json.h"
#include "sphys/tools/run_experiment.h"
#include "sphys/tools/scene.h"
#include "sphys/tools/tree_cache.h"

namespace sphys::python {
namespace {

using tools::RowResult;

tools::ExperimentRow row_from(const std::string& id) {
  const std::vector<tools::ExperimentRow> rows = tools::parse_rows(id);
  if (rows.size() != 1) throw Error("row: expected one row id such as 'd2-4x25', got '" + id + "'");
  return rows.front();
}

std::vector<tools::RowSummary> summaries_of(const std::vector<RowResult>& results) {
  std::vector<tools::RowSummary> summaries;
  for (const RowResult& result : results) summaries.push_back(tools::summarize(result));
  return summaries;
}

}  // namespace

void bind_experiment(py::module_& m) {
  m.def(
      "paper_table",
      [] {
        py::list rows;
        for (const tools::PaperRow& paper : tools::paper_table()) {
          py::dict row;
          row["id"] = paper.row.id();
          row["depth"] = paper.row.depth;
          row["stacks"] = paper.row.stacks;
          row["per_stack"] = paper.row.per_stack;
          row["contacts_per_frame"] = paper.contacts_per_frame;
          row["fps"] = paper.fps;
          row["frame_time_sd_ms"] = paper.frame_time_sd_ms;
          rows.append(row);
        }
        return rows;
      },
      "The paper's Table 1, a dict per row in its printed order.");
  m.def(
      "paper_statistics",
      [] { return from_json_text(tools::statistics_json(tools::paper_statistics())); },
      "The paper's §5 statistics (shares in %, their spread in percentage points).");
  m.def(
      "experiment_rows",
      [](const std::optional<std::string>& ids) {
        std::vector<std::string> out;
        if (ids) {
          for (const tools::ExperimentRow& row : tools::parse_rows(*ids)) out.push_back(row.id());
        } else {
          for (const tools::PaperRow& paper : tools::paper_table()) out.push_back(paper.row.id());
        }
        return out;
      },
      py::arg("ids") = std::nullopt,
      "Row ids in the paper's order: all eight, or those of a comma-separated list "
      "('d2-4x25,...').");

  py::class_<RowResult>(m, "RowResult", "What one run of one row of the experiment measured.")
      .def_property_readonly(
          "row", [](const RowResult& r) { return r.row.id(); },
          "The row's id, e.g. 'd2-4x25' (depth 2, 4 stacks of 25).")
      .def_property_readonly(
          "frames",
          [](const RowResult& r) {
            const auto n = static_cast<py::ssize_t>(r.frames.size());
            py::array_t<double> step({n}), detection({n}), response({n});
            py::array_t<std::uint32_t> contacts({n});
            for (py::ssize_t i = 0; i < n; ++i) {
              const tools::FrameSample& f = r.frames[static_cast<std::size_t>(i)];
              step.mutable_at(i) = f.step_ms;
              detection.mutable_at(i) = f.detection_ms;
              response.mutable_at(i) = f.response_ms;
              contacts.mutable_at(i) = f.contacts;
            }
            py::dict d;
            d["step_ms"] = step;
            d["detection_ms"] = detection;
            d["response_ms"] = response;
            d["contacts"] = contacts;
            return d;
          },
          "Per frame, as arrays: step_ms, detection_ms, response_ms (ms) and contacts.")
      .def(
          "summary", [](const RowResult& r) { return from_json_text(tools::row_result_json(r)); },
          "The row as `sphys experiment --json` gives it: Table 1's figures (contacts per frame, "
          "FPS of the physics alone, frame-time sd, detection and response shares in %), the "
          "bodies, and the plausibility figures (penetration, rest, jitter).")
      .def("__repr__", [](const RowResult& r) {
        return "<sphys.RowResult " + r.row.id() + ": " + std::to_string(r.frames.size()) +
               " frames>";
      });

  m.def(
      "run_experiment_row",
      [](const std::string& id, int frames, const std::string& ground, const std::string& response,
         const std::optional<std::string>& contacts, bool cache) {
        tools::ExperimentOptions options;
        options.frames = frames;
        options.ground = tools::parse_ground_option(ground, "ground");
        options.mode.response = tools::parse_response_mode(response);
        if (contacts) options.mode.contacts = tools::parse_contact_set(*contacts);
        if (cache) options.cache_dir = tools::default_cache_dir();
        const tools::ExperimentRow row = row_from(id);
        py::gil_scoped_release unlocked;
        return tools::run_experiment_row(row, options);
      },
      py::arg("row"), py::kw_only(), py::arg("frames") = 880, py::arg("ground") = "octree",
      py::arg("response") = "paper", py::arg("contacts") = std::nullopt, py::arg("cache") = true,
      "Runs one row of the paper's evaluation ('d2-4x25') as `sphys experiment` does: frames "
      "steps, the paper's octree ground or 'plane', the paper's response or 'plausible'. The GIL "
      "is released for the run.");
  m.def(
      "experiment_statistics",
      [](const std::vector<RowResult>& results) {
        return from_json_text(
            tools::statistics_json(tools::compute_statistics(summaries_of(results))));
      },
      py::arg("results"),
      "The §5 statistics of our rows, as paper_statistics() gives the paper's.");
  m.def(
      "experiment_text",
      [](const std::vector<RowResult>& results, const std::string& response,
         const std::optional<std::string>& contacts) {
        tools::ExperimentMode mode;
        mode.response = tools::parse_response_mode(response);
        if (contacts) mode.contacts = tools::parse_contact_set(*contacts);
        return tools::comparison_text(results, mode);
      },
      py::arg("results"), py::kw_only(), py::arg("response") = "paper",
      py::arg("contacts") = std::nullopt,
      "Table 1 with the paper's figures beside ours and the statistics, as `sphys experiment` "
      "prints them.");
}

}  // namespace sphys::python
