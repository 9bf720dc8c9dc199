#include "read_off.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/input_file.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

// The fewest bytes a number takes in the file: one digit and one separator. unit: bytes
constexpr std::uint64_t kMinNumberBytes = 2;

// Yields the file's meaningful lines (comments and blank lines skipped) with their numbers.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path)
      : path_(path), file_(open_input_file(path, InputKind::kMesh)) {}

  // The next non-empty line with comments removed, as a stream; throws at the end of the file.
  std::istringstream next(const char* expected) {
    std::string line;
    while (std::getline(file_.stream, line)) {
      ++number_;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      if (line.find_first_not_of(" \t\r") != std::string::npos) return std::istringstream(line);
    }
    throw Error::at_line(path_, number_, std::string("file ends early: expected ") + expected);
  }

  [[nodiscard]] Error error(const std::string& problem) const {
    return Error::at_line(path_, number_, problem);
  }
  // unit: bytes
  [[nodiscard]] std::uint64_t file_size() const { return file_.size; }

 private:
  std::filesystem::path path_;
  InputFile file_;
  std::size_t number_ = 0;
};

}  // namespace

TriangleMesh read_off(const std::filesystem::path& path) {
  LineReader reader(path);
  std::istringstream header = reader.next("the OFF header");
  std::string keyword;
  header >> keyword;
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0) {
    const bool printable = std::all_of(keyword.begin(), keyword.end(), [](char c) {
      return std::isprint(static_cast<unsigned char>(c)) != 0;
    });
    throw reader.error(printable && keyword.size() < 40
                           ? "not an OFF file: the first word is '" + keyword + "', expected 'OFF'"
                           : "not an OFF file: it starts with binary data, expected 'OFF'");
  }

  // The counts may follow the keyword on the same line.
  long long vertex_count = -1;
  long long face_count = -1;
  if (header >> std::ws; header.peek() == 'B') {
    throw reader.error("binary OFF files are not supported; save it as ASCII OFF");
  }
  if (!(header >> vertex_count)) {
    std::istringstream counts = reader.next("the vertex, face and edge counts");
    counts >> vertex_count;
    counts >> face_count;
  } else {
    header >> face_count;
  }
  if (vertex_count < 0 || face_count < 0) {
    throw reader.error("expected non-negative vertex and face counts");
  }
  // A vertex count the file cannot hold is refused before the vertices are allocated: a vertex
  // line holds at least 3 numbers, each a digit and a separator. Faces are not allocated ahead,
  // so a face count too large for the file ends at the line where the file does.
  constexpr std::uint64_t kVertexLineBytes = 3 * kMinNumberBytes;
  if (static_cast<std::uint64_t>(vertex_count) > (reader.file_size() + 1) / kVertexLineBytes) {
    throw reader.error("the header announces " + std::to_string(vertex_count) +
                       " vertices, more than the file's " + std::to_string(reader.file_size()) +
                       " bytes can hold");
  }

  TriangleMesh mesh;
  mesh.name = path.string();
  mesh.vertices.reserve(static_cast<std::size_t>(vertex_count));
  for (long long i = 0; i < vertex_count; ++i) {
    std::istringstream line = reader.next("a vertex");
    Vec3d v;
    // Read as text first: streams reject "nan", and we want to say what the value was.
    for (int k = 0; k < 3; ++k) {
      std::string word;
      if (!(line >> word)) throw reader.error("a vertex needs three coordinates");
      try {
        std::size_t used = 0;
        v[k] = std::stod(word, &used);
        if (used != word.size()) throw std::invalid_argument(word);
      } catch (const std::logic_error&) {  // stod's invalid_argument and out_of_range
        throw reader.error("coordinate '" + word + "' is not a number");
      }
      if (!std::isfinite(v[k])) throw reader.error("non-finite coordinate '" + word + "'");
    }
    mesh.vertices.push_back(v);
  }

  for (long long f = 0; f < face_count; ++f) {
    std::istringstream line = reader.next("a face");
    long long corners = 0;
    if (!(line >> corners) || corners < 3) {
      throw reader.error("a face needs a corner count of at least 3");
    }
    std::vector<std::uint32_t> face;
    for (long long k = 0; k < corners; ++k) {
      long long index = -1;
      if (!(line >> index)) throw reader.error("face has fewer indices than its corner count");
      if (index < 0 || index >= vertex_count) {
        throw reader.error("face index " + std::to_string(index) +
                           " is out of range (the file has " + std::to_string(vertex_count) +
                           " vertices)");
      }
      face.push_back(static_cast<std::uint32_t>(index));
    }
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      mesh.triangles.push_back({face[0], face[k], face[k + 1]});
    }
  }
  return mesh;
}

}  // namespace sphys::tools
