// Each pipeline's stages are the ones docs/architecture.md lists for its mode, in its order: the
// stage tables are the step's table of contents, so a stage added, removed or moved shows there.
#include "world/pipeline.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

namespace sphys {
namespace {

std::string architecture_text() {
  const std::filesystem::path path =
      std::filesystem::path(__FILE__).parent_path() / "../../docs/architecture.md";
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "cannot open " << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The first cell of each row of the first table after `heading` (its header and rule left out).
std::vector<std::string> stage_rows(const std::string& text, std::string_view heading) {
  std::vector<std::string> rows;
  std::size_t at = text.find(heading);
  if (at == std::string::npos) return rows;
  at = text.find("\n| stage |", at);
  if (at == std::string::npos) return rows;
  for (at = text.find('\n', at + 1) + 1; text.compare(at, 2, "| ") == 0;
       at = text.find('\n', at) + 1) {
    const std::size_t end = text.find(" |", at + 2);
    std::string cell = text.substr(at + 2, end - at - 2);
    if (cell.find("---") == std::string::npos) rows.push_back(std::move(cell));
  }
  return rows;
}

// Every stage has a row starting with its name, in the pipeline's order, and every row belongs to
// a stage (one stage may take several rows, as detection does).
void expect_documented(const Pipeline& pipeline, std::string_view heading) {
  const std::vector<std::string> rows = stage_rows(architecture_text(), heading);
  ASSERT_FALSE(rows.empty()) << heading;
  std::size_t row = 0;
  for (const Stage& stage : pipeline.pass) {
    ASSERT_LT(row, rows.size()) << heading << ": no row for stage '" << stage.name << "'";
    EXPECT_TRUE(rows[row].starts_with(stage.name))
        << heading << ": row '" << rows[row] << "' where stage '" << stage.name << "' is next";
    for (++row; row < rows.size() && rows[row].starts_with(stage.name); ++row) {
    }
  }
  EXPECT_EQ(row, rows.size()) << heading << ": a row for no stage: '"
                              << (row < rows.size() ? rows[row] : "") << "'";
}

TEST(Pipeline, TheArchitectureListsEachModesStagesInOrder) {
  expect_documented(paper_pipeline(), "**Paper mode**");
  expect_documented(plausible_pipeline(), "**Plausible mode**");
}

}  // namespace
}  // namespace sphys
