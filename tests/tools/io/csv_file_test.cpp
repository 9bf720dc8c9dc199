#include "sphys/tools/csv_file.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sphys/error.h"
#include "support/temp_file.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;
using sphys::test::files_in;
using sphys::test::read_whole;
using testing::AllOf;
using testing::ElementsAre;
using testing::HasSubstr;
using testing::IsEmpty;
using testing::SizeIs;

using Table = std::vector<std::vector<std::string>>;
using Rows = std::vector<std::vector<double>>;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// The records of RFC 4180 text, as a spreadsheet reads them: fields split at commas outside
// quotes, records at line ends outside quotes, "" inside quotes meaning one quote.
Table parse_csv(const std::string& text) {
  Table records;
  std::vector<std::string> record;
  std::string field;
  bool in_quotes = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_quotes) {
      if (c != '"') {
        field += c;
      } else if (i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else {
        in_quotes = false;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',' || c == '\n') {
      record.push_back(field);
      field.clear();
      if (c == '\n') {
        records.push_back(record);
        record.clear();
      }
    } else {
      field += c;
    }
  }
  EXPECT_FALSE(in_quotes) << "unterminated quote";
  EXPECT_TRUE(field.empty() && record.empty()) << "the last record does not end with a line end";
  return records;
}

// A whole field as a double, as a program reading the file would take it.
double parse_number(const std::string& field) {
  double value = 0.0;
  const char* last = field.data() + field.size();
  const auto [end, ec] = std::from_chars(field.data(), last, value);
  EXPECT_TRUE(end == last && ec == std::errc()) << "not a number: '" << field << "'";
  return value;
}

// Writes the table and returns the file's text.
std::string written(const std::vector<std::string>& columns, const Rows& rows) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "table.csv";
  write_csv(file, columns, rows);
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
  return read_whole(file);
}

TEST(CsvFile, ValuesReadBackBitForBit) {
  // Random bit patterns cover every exponent, subnormals and both signs.
  std::mt19937_64 rng(20080316);
  Rows rows;
  while (rows.size() < 2000) {
    std::vector<double> row;
    while (row.size() < 3) {
      const double value = std::bit_cast<double>(rng());
      if (std::isfinite(value)) row.push_back(value);
    }
    rows.push_back(row);
  }
  rows.push_back(
      {-0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max()});
  rows.push_back({0.1, 1.0 / 3.0, std::numeric_limits<double>::lowest()});
  rows.push_back({0x1p53 - 1, 0x1p53, 0x1p53 + 2});

  const Table table = parse_csv(written({"a", "b", "c"}, rows));
  ASSERT_THAT(table, SizeIs(rows.size() + 1));
  EXPECT_THAT(table[0], ElementsAre("a", "b", "c"));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_THAT(table[i + 1], SizeIs(3));
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(parse_number(table[i + 1][k])),
                std::bit_cast<std::uint64_t>(rows[i][k]))
          << table[i + 1][k];
    }
  }
}

TEST(CsvFile, ExactText) {
  EXPECT_EQ(written({"frame", "time", "x"}, {{880, 14.666666666666666, -0.25}, {0, 0.1, 1e-5}}),
            "frame,time,x\n880,14.666666666666666,-0.25\n0,0.1,1e-05\n");
}

TEST(CsvFile, IntegersBelowTwoToThe53AreWrittenWhole) {
  EXPECT_EQ(written({"n"}, {{880}, {-3}, {0}, {-0.0}, {1e15}, {0x1p53 - 1}, {1e16}, {1e300}}),
            "n\n880\n-3\n0\n-0\n1000000000000000\n9007199254740991\n1e+16\n1e+300\n");
}

TEST(CsvFile, NonFiniteValues) {
  const std::string text = written({"a", "b", "c", "d"}, {{kNan, -kNan, kInf, -kInf}});
  EXPECT_EQ(text, "a,b,c,d\nnan,nan,inf,-inf\n");
  const Table table = parse_csv(text);
  EXPECT_TRUE(std::isnan(parse_number(table[1][0])));
  EXPECT_EQ(parse_number(table[1][2]), kInf);
  EXPECT_EQ(parse_number(table[1][3]), -kInf);
}

TEST(CsvFile, ColumnNamesAreQuotedWhenNeeded) {
  const std::vector<std::string> columns = {
      "plain", "a,b", "say \"hi\"", "two\nlines", "cr\r", "with space", "", "\"", "h\xC3\xA9llo"};
  const std::string text = written(columns, {std::vector<double>(columns.size(), 1.0)});
  EXPECT_EQ(text.substr(0, text.find("\n1,")),
            "plain,\"a,b\",\"say \"\"hi\"\"\",\"two\nlines\",\"cr\r\",with space,,\"\"\"\","
            "h\xC3\xA9llo");
  const Table table = parse_csv(text);
  ASSERT_THAT(table, SizeIs(2));
  EXPECT_EQ(table[0], columns);
}

// Text and numbers in one table: text as the column names are, numbers as in a numeric table.
TEST(CsvFile, MixedCellsKeepTextAndNumbers) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "mixed.csv";
  const std::vector<std::string> columns = {"engine", "median_ms", "command"};
  const std::vector<std::vector<CsvCell>> rows = {
      {std::string("sphys:2"), 0.125, std::string("sphys-compare --layouts 4x25,8x10")},
      {std::string("say \"ode\""), 880.0, std::string("")}};
  write_csv(file, columns, rows);
  EXPECT_EQ(read_whole(file),
            "engine,median_ms,command\n"
            "sphys:2,0.125,\"sphys-compare --layouts 4x25,8x10\"\n"
            "\"say \"\"ode\"\"\",880,\n");
  const std::vector<std::vector<CsvCell>> short_row = {{std::string("sphys")}};
  EXPECT_THROW(write_csv(file, columns, short_row), Error);
}

TEST(CsvFile, HeaderOnly) { EXPECT_EQ(written({"frame", "time"}, {}), "frame,time\n"); }

TEST(CsvFile, ReplacesAnExistingFile) {
  const test::TempDir dir;
  const fs::path file = dir.write("table.csv", std::string(100000, 'x'));
  const std::vector<std::string> columns = {"x"};
  write_csv(file, columns, Rows{{1.5}});
  EXPECT_EQ(read_whole(file), "x\n1.5\n");
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(CsvFileErrors, RowWithTheWrongNumberOfValues) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "table.csv";
  const std::vector<std::string> columns = {"a", "b", "c"};
  try {
    write_csv(file, columns, Rows{{1, 2, 3}, {1, 2}, {1, 2, 3}});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(),
                AllOf(HasSubstr(file.string() + ": "),
                      HasSubstr("row 1 (counting from 0) has 2 values, but there are 3 columns")));
  }
  EXPECT_THROW(write_csv(file, columns, Rows{{1, 2, 3, 4}}), Error);
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(CsvFileErrors, NoColumns) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "table.csv";
  try {
    write_csv(file, {}, Rows{});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), AllOf(HasSubstr(file.string() + ": "),
                                    HasSubstr("a CSV table needs at least one column")));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(CsvFileErrors, MissingDirectory) {
  const test::TempDir dir;
  const std::vector<std::string> columns = {"x"};
  try {
    write_csv(dir.path() / "absent" / "table.csv", columns, Rows{{1}});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(),
                AllOf(HasSubstr("table.csv: "), HasSubstr("the directory does not exist")));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

}  // namespace
}  // namespace sphys::tools
