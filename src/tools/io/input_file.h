#pragma once

// Every file sphys reads is checked here before anything opens it: only a regular file of a
// bounded size gets through. A named pipe would block open() until a writer came, a device such
// as /dev/zero reads without end, and a sparse file of gigabytes costs as much time and memory
// as a real one before its first error; all three are refused at once, naming the file.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace sphys::tools {

// What a file is read as: it sets the size limit and the words of the messages.
enum class InputKind { kMesh, kSphereTree, kScene, kRecording, kRobot };

// The largest file of each kind sphys reads. unit: bytes
//
// Meshes: 1 GiB is 21 million triangles of binary STL or some 12 million of ASCII PLY or OFF,
// far more than decimation and the tree builders handle in reasonable time (the bunny is 3 MB).
constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t{1} << 30;
// .sph files: 10 million node lines (sph_file.cpp's kMaxSlots) of up to about 100 characters.
constexpr std::uint64_t kMaxSphereTreeFileBytes = std::uint64_t{1} << 30;
// Scenes are read whole into memory and parsed as JSON; 10,000 bodies take about 2 MB.
constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t{64} << 20;
// Recordings are read whole into memory: 4 GiB is 150 million body poses (28 bytes each).
constexpr std::uint64_t kMaxRecordingFileBytes = std::uint64_t{4} << 30;
// Robot files (URDF, and the sphere files `sphys spherize` writes) are read whole as XML or YAML;
// a large robot's URDF is some 100 kB.
constexpr std::uint64_t kMaxRobotFileBytes = std::uint64_t{64} << 20;

[[nodiscard]] std::uint64_t max_file_bytes(InputKind kind);

// Why `path` cannot be read as `kind` ("no such file", "is a directory, not a mesh file", "is a
// named pipe (FIFO), not a regular file", "is 2 GiB, more than the 1 GiB a mesh file may
// have", ...), or nothing when it is a regular file within the limit. Never opens the file.
[[nodiscard]] std::optional<std::string> input_file_problem(const std::filesystem::path& path,
                                                            InputKind kind);

// The size of `path` in bytes once input_file_problem() found nothing; otherwise throws
// sphys::Error "<path>: <problem>".
std::uint64_t check_input_file(const std::filesystem::path& path, InputKind kind);

struct InputFile {
  std::ifstream stream;    // binary mode
  std::uint64_t size = 0;  // unit: bytes
};

// Checks the file as check_input_file() does, then opens it for reading.
[[nodiscard]] InputFile open_input_file(const std::filesystem::path& path, InputKind kind);

// The whole file, checked first. Throws sphys::Error naming the file when it cannot be read.
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, InputKind kind);

}  // namespace sphys::tools
