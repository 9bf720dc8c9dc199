#include "json_document.h"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// Arrays and objects nested deeper are refused as they open. A scene's deepest value, a body's
// orientation axis, is 5 deep; each open container keeps its JSON pointer, so without a bound
// 10^5 unclosed '[' (100 kB) took 30 s and 9.8 GB.
constexpr std::size_t kMaxNesting = 16;

// The line and column (both from 1) of the character at `offset`, or of the last one when the
// offset is past the end.
std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t offset) {
  if (text.empty()) return {1, 1};
  offset = std::min(offset, text.size() - 1);
  const std::string_view before = text.substr(0, offset);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t newline = before.rfind('\n');
  const std::size_t line_start = newline == std::string_view::npos ? 0 : newline + 1;
  return {line, offset - line_start + 1};
}

// The word of letters around `offset` with the sign before it, and where it begins: what a writer
// of "NaN" or "-Infinity" meant as a number.
struct Word {
  std::size_t begin = 0;
  std::string text;
};

Word word_at(std::string_view text, std::size_t offset) {
  const auto is_letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  std::size_t begin = std::min(offset, text.size());
  while (begin > 0 && is_letter(text[begin - 1])) --begin;
  if (begin > 0 && (text[begin - 1] == '-' || text[begin - 1] == '+')) --begin;
  std::size_t end = std::min(offset, text.size());
  while (end < text.size() && is_letter(text[end])) ++end;
  return {begin, std::string(text.substr(begin, end - begin))};
}

bool names_non_finite(std::string word) {
  if (!word.empty() && (word.front() == '-' || word.front() == '+')) word.erase(0, 1);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word == "nan" || word == "inf" || word == "infinity";
}

// nlohmann's explanation without its "[json.exception...] parse error at line L, column C: "
// prefix, which our message replaces.
std::string nlohmann_reason(std::string_view what) {
  if (what.starts_with('[')) what.remove_prefix(std::min(what.find("] ") + 2, what.size()));
  if (what.starts_with("parse error")) {
    const std::size_t colon = what.find(": ");
    if (colon != std::string_view::npos) what.remove_prefix(colon + 2);
  }
  return std::string(what);
}

// Builds the document as nlohmann's own parser does, and in addition refuses duplicate keys
// (JSON leaves their meaning open and nlohmann keeps the last one silently) and reports every
// syntax error, NaN and Infinity included, and every number beyond a double with its line and
// column.
class DocumentBuilder final : public nlohmann::json_sax<Json> {
 public:
  DocumentBuilder(std::string_view text, const fs::path& name, std::span<const ArrayLimit> limits)
      : text_(text), name_(name), limits_(limits) {}

  [[nodiscard]] Json take() { return std::move(root_); }

  bool null() override { return add(nullptr); }
  bool boolean(bool value) override { return add(value); }
  bool number_integer(number_integer_t value) override { return add(value); }
  bool number_unsigned(number_unsigned_t value) override { return add(value); }
  bool number_float(number_float_t value, const string_t& /*text*/) override { return add(value); }
  bool string(string_t& value) override { return add(std::move(value)); }
  bool binary(binary_t& value) override { return add(std::move(value)); }
  bool start_object(std::size_t /*size*/) override { return open(Json::object()); }
  bool start_array(std::size_t /*size*/) override { return open(Json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& key) override {
    const Container& object = open_.back();
    if (object.value->contains(key)) {
      throw Error::at_json_path(name_, object.pointer + "/" + pointer_token(key), "duplicate key");
    }
    key_ = std::move(key);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token,
                   const Json::exception& error) override {
    constexpr int kNumberOverflow = 406;
    // nlohmann's position counts the characters read, the offending one included; for a number
    // beyond a double it is the index of the character after the number.
    std::size_t offset = position == 0 ? 0 : position - 1;
    std::string reason;
    if (error.id == kNumberOverflow) {
      offset = position >= token.size() ? position - token.size() : 0;
      reason = "the number " + token + " is beyond the range of a double";
    } else if (const Word word = word_at(text_, offset); names_non_finite(word.text)) {
      offset = word.begin;
      reason = word.text + " is not a number in JSON; every number must be finite";
    } else {
      reason = "not valid JSON: " + nlohmann_reason(error.what());
    }
    const auto [line, column] = line_and_column(text_, offset);
    throw Error::at_line(name_, line, "column " + std::to_string(column) + ": " + reason);
  }

 private:
  struct Container {
    Json* value;
    std::string pointer;
  };

  // Counted as they are read, so that a file of millions of elements stops here, at once.
  void check_limit(const Container& array) const {
    for (const ArrayLimit& limit : limits_) {
      if (array.pointer == limit.pointer && array.value->size() == limit.max_size) {
        throw Error::at_json_path(
            name_, array.pointer,
            "more than " + std::to_string(limit.max_size) + " " + std::string(limit.refusal));
      }
    }
  }

  // Puts a value where the parser is: the root, the next element of the innermost array or the
  // value of the key just read; returns it with its JSON pointer.
  Container place(Json value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return {&root_, ""};
    }
    const Container& parent = open_.back();
    if (parent.value->is_array()) {
      check_limit(parent);
      const std::string pointer = parent.pointer + "/" + std::to_string(parent.value->size());
      parent.value->push_back(std::move(value));
      return {&parent.value->back(), pointer};
    }
    Json& slot = (*parent.value)[key_];
    slot = std::move(value);
    return {&slot, parent.pointer + "/" + pointer_token(key_)};
  }

  bool add(Json value) {
    place(std::move(value));
    return true;
  }
  // Only the innermost container grows, so the pointers to the enclosing ones stay valid.
  bool open(Json container) {
    Container placed = place(std::move(container));
    if (open_.size() == kMaxNesting) {
      throw Error::at_json_path(
          name_, placed.pointer,
          "arrays and objects nested more than " + std::to_string(kMaxNesting) + " deep");
    }
    open_.push_back(std::move(placed));
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  std::string_view text_;
  const fs::path& name_;
  std::span<const ArrayLimit> limits_;
  Json root_;
  std::vector<Container> open_;
  std::string key_;
};

}  // namespace

std::string pointer_token(std::string_view key) {
  std::string out;
  for (const char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += std::iscntrl(static_cast<unsigned char>(c)) != 0 ? '?' : c;
    }
  }
  return out;
}

Json parse_json(std::string_view text, const fs::path& name, std::span<const ArrayLimit> limits) {
  DocumentBuilder builder(text, name, limits);
  Json::sax_parse(text.begin(), text.end(), &builder);
  return builder.take();
}

}  // namespace sphys::tools
