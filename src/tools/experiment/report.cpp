#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/tools/csv_file.h"
#include "sphys/tools/experiment.h"
#include "sphys/tools/scene.h"

namespace sphys::tools {
namespace {

// A figure with a fixed number of decimals; "n/a" for NaN, so that a figure a run could not give
// never reads as a number.
std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "n/a";
  // Room for the longest fixed double: 309 digits, a sign, a point and the decimals.
  std::array<char, 400> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::fixed, decimals);
  return {buffer.data(), result.ptr};
}

// A correlation as the paper prints one: two decimals and always a sign.
std::string signed_fixed(double value) {
  const std::string text = fixed(value, 2);
  return std::isnan(value) || std::signbit(value) ? text : "+" + text;
}

std::string objects(const ExperimentRow& row) {
  return std::to_string(row.stacks) + " × " + std::to_string(row.per_stack);
}

const PaperRow* find_paper_row(const ExperimentRow& row) {
  const std::span<const PaperRow> table = paper_table();
  const auto found = std::ranges::find(table, row, &PaperRow::row);
  return found == table.end() ? nullptr : &*found;
}

// Results in the order of Table 1; rows the paper did not run follow, in the order given.
std::vector<const RowResult*> in_paper_order(std::span<const RowResult> results) {
  const std::span<const PaperRow> table = paper_table();
  const auto position = [&](const RowResult* result) {
    return std::ranges::find(table, result->row, &PaperRow::row) - table.begin();
  };
  std::vector<const RowResult*> ordered;
  for (const RowResult& result : results) ordered.push_back(&result);
  std::ranges::stable_sort(ordered, {}, position);
  return ordered;
}

struct Column {
  // Plain text: `group` heads neighbouring columns of the same group on a first header line,
  // `name` the column on a second.
  std::string group;
  std::string name;
  std::string markdown_title;  // the one header line in Markdown
  bool right_aligned = true;
};

struct Table {
  std::vector<Column> columns;
  std::vector<std::vector<std::string>> rows;
};

// "3 of 80": a count of the row's bunnies.
std::string of_bodies(std::uint32_t count, const RowResult& result) {
  return std::to_string(count) + " of " + std::to_string(result.bodies);
}

Table table1(std::span<const RowResult> results) {
  Table table;
  table.columns = {
      {"", "depth", "depth", true},
      {"", "objects", "objects", false},
      {"contacts/frame", "paper", "contacts/frame (paper)", true},
      {"contacts/frame", "ours", "contacts/frame (ours)", true},
      {"FPS", "paper", "FPS (paper)", true},
      {"FPS", "ours", "FPS (ours)", true},
      {"FPS", "ours, drawn", "FPS with drawing (ours)", true},
      {"frame sd (ms)", "paper", "frame sd ms (paper)", true},
      {"frame sd (ms)", "ours", "frame sd ms (ours)", true},
      {"ours only", "bodies below plane", "bodies below plane", true},
      {"ours only", "deepest penetration (m)", "deepest penetration (m)", true},
      {"ours only", "mean penetration (m)", "mean penetration (m)", true},
      {"ours only", "at rest at the end", "bodies at rest at the end", true},
      {"ours only", "all at rest from frame", "all at rest from frame", true},
      {"ours only", "jitter (m/s)", "jitter, last 60 frames (m/s)", true},
      {"ours only", "final KE (J)", "final kinetic energy (J)", true},
  };
  for (const RowResult* result : in_paper_order(results)) {
    const RowSummary ours = summarize(*result);
    const Plausibility& plausible = result->plausibility;
    const PaperRow* paper = find_paper_row(result->row);
    const auto paper_figure = [&](double PaperRow::*figure) {
      return paper == nullptr ? std::string("-") : fixed(paper->*figure, 2);
    };
    table.rows.push_back({
        std::to_string(result->row.depth),
        objects(result->row),
        paper_figure(&PaperRow::contacts_per_frame),
        fixed(ours.contacts_per_frame, 2),
        paper_figure(&PaperRow::fps),
        fixed(ours.fps, 2),
        fixed(ours.fps_with_drawing, 2),
        paper_figure(&PaperRow::frame_time_sd_ms),
        fixed(ours.frame_time_sd_ms, 2),
        of_bodies(result->bodies_below_plane, *result),
        fixed(plausible.deepest_penetration, 4),
        fixed(plausible.mean_penetration, 4),
        of_bodies(plausible.bodies_at_rest, *result),
        plausible.all_at_rest_frame ? std::to_string(*plausible.all_at_rest_frame) : "never",
        fixed(plausible.jitter, 4),
        fixed(plausible.final_kinetic_energy, 3),
    });
  }
  return table;
}

// Summed in one order whatever the order given, so that the figures do not depend on it.
ExperimentStatistics our_statistics(std::span<const RowResult> results) {
  std::vector<RowSummary> summaries;
  for (const RowResult* result : in_paper_order(results)) summaries.push_back(summarize(*result));
  return compute_statistics(summaries);
}

Table statistics_table(std::span<const RowResult> results) {
  const ExperimentStatistics& paper = paper_statistics();
  const ExperimentStatistics ours = our_statistics(results);
  Table table;
  table.columns = {
      {"", "§5 statistic", "statistic", false},
      {"", "paper", "paper", true},
      {"", "ours", "ours", true},
  };
  const auto correlation = [&](std::string name, double ExperimentStatistics::*figure) {
    table.rows.push_back(
        {std::move(name), signed_fixed(paper.*figure), signed_fixed(ours.*figure)});
  };
  const auto percentage = [&](std::string name, double ExperimentStatistics::*figure) {
    table.rows.push_back({std::move(name), fixed(paper.*figure, 2), fixed(ours.*figure, 2)});
  };
  correlation("contacts vs FPS (r)", &ExperimentStatistics::contacts_fps_correlation);
  correlation("contacts vs frame time sd (r)",
              &ExperimentStatistics::contacts_frame_sd_correlation);
  percentage("detection share of frame time (%)", &ExperimentStatistics::detection_share_mean);
  percentage("detection share sd across rows (pp)", &ExperimentStatistics::detection_share_sd);
  percentage("response share of frame time (%)", &ExperimentStatistics::response_share_mean);
  percentage("response share sd across rows (pp)", &ExperimentStatistics::response_share_sd);
  correlation("detection share vs contacts (r)",
              &ExperimentStatistics::detection_share_contacts_correlation);
  correlation("response share vs contacts (r)",
              &ExperimentStatistics::response_share_contacts_correlation);
  return table;
}

// Columns as a terminal shows them: UTF-8 continuation bytes ("×", "§") take none.
std::size_t display_width(std::string_view text) {
  return static_cast<std::size_t>(std::ranges::count_if(
      text, [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

std::string padded(std::string_view text, std::size_t width, bool right_aligned) {
  const std::string fill(width - std::min(width, display_width(text)), ' ');
  return right_aligned ? fill + std::string(text) : std::string(text) + fill;
}

constexpr std::string_view kGap = "  ";

void append_line(std::string& out, std::string line) {
  line.erase(line.find_last_not_of(' ') + 1);
  out += line;
  out += '\n';
}

std::string text_table(const Table& table) {
  const std::vector<Column>& columns = table.columns;
  std::vector<std::size_t> widths;
  widths.reserve(columns.size());
  for (const Column& column : columns) widths.push_back(display_width(column.name));
  for (const std::vector<std::string>& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      widths[i] = std::max(widths[i], display_width(row[i]));
    }
  }

  // A group's label spans its columns; where it is wider, its last column grows to fit it.
  std::string group_line;
  for (std::size_t first = 0; first < columns.size();) {
    std::size_t last = first;
    while (last + 1 < columns.size() && columns[last + 1].group == columns[first].group) ++last;
    std::size_t span = kGap.size() * (last - first);
    for (std::size_t i = first; i <= last; ++i) span += widths[i];
    const std::size_t label = display_width(columns[first].group);
    if (label > span) {
      widths[last] += label - span;
      span = label;
    }
    if (first > 0) group_line += kGap;
    group_line += padded(columns[first].group, span, false);
    first = last + 1;
  }

  const auto line_of = [&](const std::vector<std::string>& cells) {
    std::string line;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i > 0) line += kGap;
      line += padded(cells[i], widths[i], columns[i].right_aligned);
    }
    return line;
  };

  std::string out;
  const bool grouped =
      std::ranges::any_of(columns, [](const Column& c) { return !c.group.empty(); });
  if (grouped) append_line(out, group_line);
  std::vector<std::string> names;
  names.reserve(columns.size());
  for (const Column& column : columns) names.push_back(column.name);
  append_line(out, line_of(names));
  std::size_t total = kGap.size() * (columns.size() - 1);
  for (const std::size_t width : widths) total += width;
  append_line(out, std::string(total, '-'));
  for (const std::vector<std::string>& row : table.rows) append_line(out, line_of(row));
  return out;
}

// A '|' inside a cell would end it.
std::string markdown_cell(std::string_view text) {
  std::string cell;
  for (const char c : text) {
    if (c == '|') cell += '\\';
    cell += c;
  }
  return cell;
}

std::string markdown_line(const std::vector<std::string>& cells) {
  std::string line = "|";
  for (const std::string& cell : cells) {
    line += ' ';
    line += markdown_cell(cell);
    line += " |";
  }
  line += '\n';
  return line;
}

std::string markdown_table(const Table& table) {
  std::vector<std::string> titles;
  std::string rule = "|";
  for (const Column& column : table.columns) {
    titles.push_back(column.markdown_title);
    rule += column.right_aligned ? " ---: |" : " :--- |";
  }
  std::string out = markdown_line(titles) + rule + "\n";
  for (const std::vector<std::string>& row : table.rows) out += markdown_line(row);
  return out;
}

Table runs_table(std::span<const RowResult> results) {
  Table table;
  table.columns = {
      {"", "row", "row", false},
      {"", "tree builder", "tree builder", false},
      {"", "ground", "ground", false},
      {"", "frames", "frames", true},
      {"", "every bunny above the plane", "every bunny above the plane", false},
      {"", "lowest centre at the end (m)", "lowest centre of mass at the end (m)", true},
      {"", "stopped on a non-finite state", "stopped on a non-finite state", false},
  };
  for (const RowResult* result : in_paper_order(results)) {
    const std::string above = result->bodies_below_plane == 0
                                  ? "yes"
                                  : "no: " + std::to_string(result->bodies_below_plane) + " of " +
                                        std::to_string(result->bodies) + " below";
    table.rows.push_back({
        result->row.id(),
        result->tree_builder,
        result->ground,
        std::to_string(result->frames.size()),
        above,
        fixed(result->lowest_center_y, 4),
        result->stopped_non_finite ? "yes" : "no",
    });
  }
  return table;
}

// Why bunnies ended below the plane, when some did on a ground with an edge: a newcomer should not
// read it as a fault. Empty otherwise.
std::string below_plane_note(std::span<const RowResult> results) {
  const bool fell_off = std::any_of(results.begin(), results.end(), [](const RowResult& result) {
    return result.bodies_below_plane > 0 && result.ground.starts_with("octree");
  });
  if (!fell_off) return "";
  return "\nThe bunnies below the plane slid off the octree ground's edge and fell: the paper "
         "gives its plane's structure but not its size, paper mode has no friction to stop a "
         "bunny that lands sliding, and no size of the paper's octree keeps every bunny on it "
         "(docs/experiment.md, \"The ground\", has the sizes tried). Figure 2's last frames "
         "show those that stayed; `--ground plane` keeps every bunny above the plane.\n";
}

// The paper's contacts-FPS correlation recomputed from its own Table 1.
double paper_table_contacts_fps_correlation() {
  std::vector<double> contacts;
  std::vector<double> fps;
  for (const PaperRow& row : paper_table()) {
    contacts.push_back(row.contacts_per_frame);
    fps.push_back(row.fps);
  }
  return pearson(contacts, fps);
}

// With frames drawn (--render, --render-all): the frame as the paper timed it, physics and
// drawing, and the §5 shares on that basis. Empty when no row was drawn.
Table drawing_table(std::span<const RowResult> results) {
  Table table;
  table.columns = {
      {"", "row", "row", false},
      {"frames", "drawn", "frames drawn", true},
      {"FPS", "physics", "FPS, physics only", true},
      {"FPS", "drawn", "FPS with drawing", true},
      {"share of the drawn frame (%)", "drawing", "drawing (% of the drawn frame)", true},
      {"share of the drawn frame (%)", "detection", "detection (% of the drawn frame)", true},
      {"share of the drawn frame (%)", "response", "response (% of the drawn frame)", true},
  };
  for (const RowResult* result : in_paper_order(results)) {
    const RowSummary ours = summarize(*result);
    if (std::isnan(ours.fps_with_drawing)) continue;
    table.rows.push_back(
        {result->row.id(),
         std::to_string(ours.frames_drawn) + " of " + std::to_string(result->frames.size()),
         fixed(ours.fps, 2), fixed(ours.fps_with_drawing, 2), fixed(ours.drawing_share, 1),
         fixed(ours.detection_share_drawn, 1), fixed(ours.response_share_drawn, 1)});
  }
  return table;
}

// Figure 2 of the paper is (a) the 4 × 50 scene as the bunnies begin to fall and (b) the end of
// their fall; ours shows every row's first and last frame beside those captions.
std::string figure2_section(std::span<const RowResult> results) {
  std::string out;
  bool any = false;
  for (const RowResult* result : in_paper_order(results)) {
    const std::string id = result->row.id();
    if (!result->pictures_missing.empty()) {
      out += "| " + id + " | no pictures: " + result->pictures_missing + " | |\n";
      any = true;
    } else if (!result->first_picture.empty() && !result->last_picture.empty()) {
      out += "| " + id + " | ![" + id + ", first frame](" + result->first_picture + ") | ![" + id +
             ", last frame](" + result->last_picture + ") |\n";
      any = true;
    }
  }
  if (!any) return "";
  return "\n## Figure 2\n\nThe paper's Figure 2: \"In (a) an example of a scenario with 4 stacks "
         "and 50 bunnies per stack (totalizing 200 bunnies) in the beginning of their falling, "
         "and in (b), in the end of their falling.\" Ours, every row: the frame before the first "
         "step and the last frame.\n\n| row | (a) the beginning of the fall | (b) the end |\n| "
         "--- | --- | --- |\n" +
         out;
}

// The plots drawn, each row's under its name: a run without plots (--no-plots, or no gnuplot)
// links none.
std::string plots_section(std::span<const RowResult> results,
                          std::span<const std::filesystem::path> plots) {
  const auto drawn = [&](const std::string& file) {
    return std::any_of(plots.begin(), plots.end(),
                       [&](const std::filesystem::path& plot) { return plot.filename() == file; });
  };
  std::string out;
  for (const RowResult* result : in_paper_order(results)) {
    const std::string id = result->row.id();
    const PlotFiles files = plot_files(result->row);
    std::string links;
    if (drawn(files.frame_time)) {
      links += "![" + id + ": frame time per frame](" + files.frame_time + ")\n";
    }
    if (drawn(files.contacts))
      links += "![" + id + ": contacts per frame](" + files.contacts + ")\n";
    if (!links.empty()) out += "\n### " + id + "\n\n" + links;
  }
  if (out.empty()) return out;
  return "\n## Plots\n\nThe physics step's time (ms) and the contacts, frame by frame.\n" + out;
}

// How the rows were run, one line each for the response and the contacts it saw: the figures of
// the two modes differ, and reduced contacts count fewer per frame.
std::string mode_lines(const ExperimentMode& mode) {
  std::string out = "Response: ";
  out += response_mode_name(mode.response);
  if (mode.response == ResponseMode::kPaper) {
    out += " (the impulse of eq. 4 per contact, no friction, as published)\n";
    out += "Contacts: every overlapping leaf pair (the contacts setting, ";
    out += contact_set_name(mode.contacts);
    out += ", applies to plausible mode only)\n";
    return out;
  }
  out += " (the soft step with friction, rolling resistance, contact springs and sleeping)\n";
  out += "Contacts: ";
  out += contact_set_name(mode.contacts);
  out += mode.contacts == ContactSet::kReduced
             ? " (a small manifold per body pair; contacts/frame counts the manifolds' points)\n"
             : " (one per overlapping leaf pair, as the paper makes them)\n";
  return out;
}

}  // namespace

std::string comparison_text(std::span<const RowResult> results, const ExperimentMode& mode) {
  return mode_lines(mode) +
         "\nTable 1: the paper's figures beside ours (our FPS: the physics step only, no "
         "rendering)\n\n" +
         text_table(table1(results)) + "\n" + text_table(statistics_table(results));
}

std::string markdown_report(std::span<const RowResult> results, const std::string& machine,
                            const ExperimentMode& mode,
                            std::span<const std::filesystem::path> plots) {
  std::string out = "# Table 1 of Rocha & Rodrigues (SAC 2008), reproduced\n\n";
  out += "Machine: " + machine + "\n\n";
  out += mode_lines(mode) + "\n";
  out +=
      "FPS (ours) counts the physics step alone; the paper's frames included rendering, so its "
      "FPS and frame time figures cover more work. FPS with drawing (ours) counts the frames "
      "drawn offscreen as well (`sphys experiment --render`, " +
      std::to_string(kDrawnFrameWidth) + " × " + std::to_string(kDrawnFrameHeight) +
      " pixels); n/a when the frames were not drawn.\n";
  out += "\n## Table 1\n\n" + markdown_table(table1(results));
  if (const Table drawn = drawing_table(results); !drawn.rows.empty()) {
    out +=
        "\n## Frames drawn\n\nFrames drawn after their step, timed with it: the frame time the "
        "paper measured. `--render` draws every " +
        std::to_string(kRenderSampleStride) +
        "th frame and counts each frame not drawn at the drawn ones' mean; `--render-all` draws "
        "every frame.\n\n" +
        markdown_table(drawn);
  }
  out += "\n## Statistics (§5)\n\n" + markdown_table(statistics_table(results));
  out +=
      "\nShares are percentages of the frame time, their spread the standard deviation across "
      "rows in percentage points; correlations are Pearson's r across rows. The paper prints "
      "+0.75 for contacts vs FPS although its text says FPS falls as contacts rise; its own "
      "Table 1 gives r = " +
      signed_fixed(paper_table_contacts_fps_correlation()) + ".\n";
  out += "\n## Runs\n\n" + markdown_table(runs_table(results));
  out += below_plane_note(results);
  out += figure2_section(results);
  out += plots_section(results, plots);
  return out;
}

void write_row_csv(const std::filesystem::path& path, const RowResult& result) {
  const std::array<std::string, 6> columns = {"frame",       "step_ms",  "detection_ms",
                                              "response_ms", "contacts", "render_ms"};
  std::vector<std::vector<double>> rows;
  rows.reserve(result.frames.size());
  for (std::size_t i = 0; i < result.frames.size(); ++i) {
    const FrameSample& frame = result.frames[i];
    rows.push_back({static_cast<double>(i + 1), frame.step_ms, frame.detection_ms,
                    frame.response_ms, static_cast<double>(frame.contacts), frame.render_ms});
  }
  write_csv(path, columns, rows);
}

}  // namespace sphys::tools
