#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace sphys::tools {

// Writes a table as CSV (RFC 4180, lines ending in "\n"): a header line of column names, then
// one line per row. Numbers are written in the shortest form that reads back to the same double,
// in the "C" locale whatever the program's: integers below 2^53 in magnitude without a decimal
// point or exponent ("880"), others as std::to_chars gives them ("0.1", "1e-05", "1e+300");
// "nan", "inf" and "-inf" for the values that are not finite. A column name or text cell holding
// a comma, a double quote or a line break is put in double quotes, its quotes doubled.
//
// The file is written whole or not at all. Throws sphys::Error naming the file when there are no
// columns, a row's number of values differs from the number of columns, or the file cannot be
// written.
void write_csv(const std::filesystem::path& path, std::span<const std::string> columns,
               std::span<const std::vector<double>> rows);

// A cell of a table whose columns mix numbers and text (e.g. a benchmark's engine and machine).
using CsvCell = std::variant<double, std::string>;
// The same with cells of numbers or text: numbers written as above, text as it is (quoted when
// it must be).
void write_csv(const std::filesystem::path& path, std::span<const std::string> columns,
               std::span<const std::vector<CsvCell>> rows);

}  // namespace sphys::tools
