#include "sphys/tools/csv_file.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <string_view>

#include "atomic_file.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Every integer below this magnitude is a double exactly, so it can be written as one.
constexpr double kExactIntegers = 0x1p53;

void append_text(std::string& line, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    line += text;
    return;
  }
  line += '"';
  for (const char c : text) {
    if (c == '"') line += '"';
    line += c;
  }
  line += '"';
}

void append_cell(std::string& line, double value) {
  // to_chars alone gives "nan" or "-nan" depending on the sign bit, which means nothing here.
  if (std::isnan(value)) {
    line += "nan";
    return;
  }
  std::array<char, 32> buffer{};
  char* const first = buffer.data();
  char* const last = first + buffer.size();
  // Shortest form prefers an exponent for large integers ("1e+15"); fixed keeps them whole.
  const bool exact_integer = std::abs(value) < kExactIntegers && std::trunc(value) == value;
  const auto result = exact_integer ? std::to_chars(first, last, value, std::chars_format::fixed)
                                    : std::to_chars(first, last, value);
  line.append(first, result.ptr);
}

void append_cell(std::string& line, const CsvCell& cell) {
  if (const double* number = std::get_if<double>(&cell)) {
    append_cell(line, *number);
  } else {
    append_text(line, std::get<std::string>(cell));
  }
}

template <class Cell>
void write_table(const fs::path& path, std::span<const std::string> columns,
                 std::span<const std::vector<Cell>> rows) {
  if (columns.empty()) throw Error::in_file(path, "a CSV table needs at least one column");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != columns.size()) {
      throw Error::in_file(path, "row " + std::to_string(i) + " (counting from 0) has " +
                                     std::to_string(rows[i].size()) + " values, but there are " +
                                     std::to_string(columns.size()) + " columns");
    }
  }
  write_file_atomically(path, [&](std::ostream& out) {
    std::string line;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      if (k > 0) line += ',';
      append_text(line, columns[k]);
    }
    line += '\n';
    out << line;
    for (const std::vector<Cell>& row : rows) {
      line.clear();
      for (std::size_t k = 0; k < row.size(); ++k) {
        if (k > 0) line += ',';
        append_cell(line, row[k]);
      }
      line += '\n';
      out << line;
    }
  });
}

}  // namespace

void write_csv(const fs::path& path, std::span<const std::string> columns,
               std::span<const std::vector<double>> rows) {
  write_table(path, columns, rows);
}

void write_csv(const fs::path& path, std::span<const std::string> columns,
               std::span<const std::vector<CsvCell>> rows) {
  write_table(path, columns, rows);
}

}  // namespace sphys::tools
