#include "input_file.h"

#include <cstdio>
#include <iterator>
#include <system_error>

#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// The words a message uses for a file of each kind: "is a directory, not a <name>".
const char* kind_name(InputKind kind) {
  switch (kind) {
    case InputKind::kMesh:
      return "mesh file";
    case InputKind::kSphereTree:
      return ".sph file";
    case InputKind::kScene:
      return "scene file";
    case InputKind::kRecording:
      return "recording";
    case InputKind::kRobot:
      return "robot file";
  }
  return "file";
}

// "64 MiB", "2 GiB", "1.5 GiB", "900 bytes".
std::string size_text(std::uint64_t bytes) {
  constexpr double kMiB = 1024.0 * 1024.0;
  constexpr double kGiB = 1024.0 * kMiB;
  char text[32];
  const auto value = static_cast<double>(bytes);
  if (value >= kGiB) {
    std::snprintf(text, sizeof text, "%.3g GiB", value / kGiB);
  } else if (value >= kMiB) {
    std::snprintf(text, sizeof text, "%.3g MiB", value / kMiB);
  } else {
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  }
  return text;
}

std::string not_regular(const fs::file_status& status, InputKind kind) {
  switch (status.type()) {
    case fs::file_type::directory:
      return std::string("is a directory, not a ") + kind_name(kind);
    case fs::file_type::fifo:
      return "is a named pipe (FIFO), not a regular file";
    case fs::file_type::character:
    case fs::file_type::block:
      return "is a device, not a regular file";
    case fs::file_type::socket:
      return "is a socket, not a regular file";
    default:
      return "is not a regular file";
  }
}

}  // namespace

std::uint64_t max_file_bytes(InputKind kind) {
  switch (kind) {
    case InputKind::kMesh:
      return kMaxMeshFileBytes;
    case InputKind::kSphereTree:
      return kMaxSphereTreeFileBytes;
    case InputKind::kScene:
      return kMaxSceneFileBytes;
    case InputKind::kRecording:
      return kMaxRecordingFileBytes;
    case InputKind::kRobot:
      return kMaxRobotFileBytes;
  }
  return 0;
}

std::optional<std::string> input_file_problem(const fs::path& path, InputKind kind) {
  if (path.empty()) return "no file name given";
  // stat() only: opening a named pipe would wait for a writer.
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) return "no such file";
  if (status.type() == fs::file_type::none || status.type() == fs::file_type::unknown) {
    return "cannot read: " + ec.message();
  }
  if (status.type() != fs::file_type::regular) return not_regular(status, kind);
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return "cannot read: " + ec.message();
  if (size > max_file_bytes(kind)) {
    return "is " + size_text(size) + ", more than the " + size_text(max_file_bytes(kind)) + " a " +
           kind_name(kind) + " may have";
  }
  return std::nullopt;
}

std::uint64_t check_input_file(const fs::path& path, InputKind kind) {
  if (const auto problem = input_file_problem(path, kind)) throw Error::in_file(path, *problem);
  std::error_code ec;
  return fs::file_size(path, ec);
}

InputFile open_input_file(const fs::path& path, InputKind kind) {
  InputFile file;
  file.size = check_input_file(path, kind);
  file.stream.open(path, std::ios::binary);
  if (!file.stream) throw Error::in_file(path, "cannot open file for reading");
  return file;
}

std::string read_input_file(const fs::path& path, InputKind kind) {
  InputFile file = open_input_file(path, kind);
  std::string bytes(static_cast<std::size_t>(file.size), '\0');
  file.stream.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  // A file that shrank since the check reads short; one that grew is read to its checked size.
  bytes.resize(static_cast<std::size_t>(file.stream.gcount()));
  if (file.stream.bad()) throw Error::in_file(path, "cannot read the file");
  return bytes;
}

}  // namespace sphys::tools
