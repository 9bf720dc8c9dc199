#include "sphys/tools/recording.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include "atomic_file.h"
#include "input_file.h"
#include "sphys/error.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// The layout of docs/file-formats.md: magic, u32 version, u32 body count, f64 time step,
// u32 frame count, u32 metadata length; then the metadata, then the frames.
constexpr std::string_view kMagic = "SPHYSREC";
constexpr std::size_t kVersionOffset = 8;
constexpr std::size_t kBodyCountOffset = 12;
constexpr std::size_t kTimeStepOffset = 16;
constexpr std::size_t kFrameCountOffset = 24;
constexpr std::size_t kMetadataLengthOffset = 28;
constexpr std::size_t kHeaderSize = 32;

// A pose is 7 f32: position x y z, then orientation w x y z.
constexpr std::size_t kPoseValues = 7;
constexpr std::size_t kPoseSize = kPoseValues * 4;
constexpr std::array<const char*, kPoseValues> kValueNames = {
    "position x",    "position y",    "position z",   "orientation w",
    "orientation x", "orientation y", "orientation z"};

// How far the length of a stored orientation may be from 1. Bodies renormalise their orientation
// every step, which leaves an error near float epsilon (1e-7); 1e-3 only catches values that are
// not rotations at all.
constexpr double kUnitLengthTolerance = 1e-3;

using PoseValues = std::array<float, kPoseValues>;

// Bytes are composed by shifts rather than copied, so the file is little-endian whatever the host.
void put_u32(char* out, std::uint32_t value) {
  for (std::size_t i = 0; i < 4; ++i) out[i] = static_cast<char>(value >> (8 * i));
}

void put_u64(char* out, std::uint64_t value) {
  for (std::size_t i = 0; i < 8; ++i) out[i] = static_cast<char>(value >> (8 * i));
}

std::uint32_t get_u32(const char* in) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    value |= std::uint32_t{static_cast<unsigned char>(in[i])} << (8 * i);
  }
  return value;
}

std::uint64_t get_u64(const char* in) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    value |= std::uint64_t{static_cast<unsigned char>(in[i])} << (8 * i);
  }
  return value;
}

// Numbers in messages in their shortest exact form ("0.5", "nan", "-inf", "1e-300").
template <typename Number>
std::string shown(Number value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

PoseValues values_of(const BodyPose& pose) {
  const Quat& q = pose.orientation;
  return {pose.position.x(), pose.position.y(), pose.position.z(), q.w(), q.x(), q.y(), q.z()};
}

// What is wrong with a pose, or nothing: what the writer refuses and the reader rejects.
std::optional<std::string> pose_problem(const PoseValues& values) {
  for (std::size_t k = 0; k < kPoseValues; ++k) {
    if (!std::isfinite(values[k])) {
      return std::string(kValueNames[k]) + " is not finite (" + shown(values[k]) + ")";
    }
  }
  double squared_length = 0.0;
  for (std::size_t k = 3; k < kPoseValues; ++k) {
    squared_length += static_cast<double>(values[k]) * static_cast<double>(values[k]);
  }
  const double length = std::sqrt(squared_length);
  if (std::abs(length - 1.0) > kUnitLengthTolerance) {
    return "orientation has length " + shown(static_cast<float>(length)) +
           ", not 1 (a rotation is a unit quaternion)";
  }
  return std::nullopt;
}

std::string pose_place(std::uint32_t frame, std::size_t body) {
  return "frame " + std::to_string(frame) + ", body " + std::to_string(body) + ": ";
}

std::optional<std::string> time_step_problem(double time_step) {
  if (std::isfinite(time_step) && time_step > 0.0) return std::nullopt;
  return "the time step must be positive and finite, got " + shown(time_step) + " s";
}

// Reads exactly `size` bytes; the sizes were checked against the file's size beforehand, so a
// short read means the file changed under us or could not be read.
void read_exactly(std::istream& in, char* out, std::size_t size, const fs::path& path) {
  in.read(out, static_cast<std::streamsize>(size));
  if (static_cast<std::size_t>(in.gcount()) != size) {
    throw Error::in_file(path, "cannot read the file (did it change while being read?)");
  }
}

// frame_count × frame_size, which may exceed 64 bits for a corrupt header.
std::string total_size_text(std::uint64_t frame_count, std::uint64_t frame_size) {
  if (frame_size != 0 && frame_count > std::numeric_limits<std::uint64_t>::max() / frame_size) {
    return "more than " + std::to_string(std::numeric_limits<std::uint64_t>::max());
  }
  return std::to_string(frame_count * frame_size);
}

// The frames announced by the header must fill the rest of the file exactly.
void check_frames_size(const fs::path& path, std::uint32_t frame_count, std::uint32_t body_count,
                       std::uint64_t available) {
  const std::uint64_t frame_size = std::uint64_t{body_count} * kPoseSize;
  const std::uint64_t whole_frames = frame_size == 0 ? frame_count : available / frame_size;
  if (whole_frames < frame_count) {
    throw Error::in_file(
        path, "truncated frames: only " + std::to_string(whole_frames) + " of " +
                  std::to_string(frame_count) + " frames are whole; " +
                  std::to_string(frame_count) + " frames of " + std::to_string(body_count) +
                  " bodies need " + total_size_text(frame_count, frame_size) +
                  " bytes after the metadata, the file has " + std::to_string(available));
  }
  const std::uint64_t expected = frame_count * frame_size;
  if (available > expected) {
    throw Error::in_file(path, std::to_string(available - expected) +
                                   " trailing bytes after the last frame (" +
                                   std::to_string(frame_count) + " frames of " +
                                   std::to_string(body_count) + " bodies)");
  }
}

}  // namespace

struct RecordingWriter::Impl {
  Impl(const fs::path& path, std::uint32_t bodies) : file(path), body_count(bodies) {}

  AtomicFile file;
  std::uint32_t body_count;
  std::uint32_t frame_count = 0;
  std::string frame_bytes;  // reused from frame to frame
  bool finished = false;
};

RecordingWriter::RecordingWriter(const fs::path& path, std::uint32_t body_count, double time_step,
                                 std::string_view metadata) {
  if (const auto problem = time_step_problem(time_step)) throw Error::in_file(path, *problem);
  if (metadata.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error::in_file(path, "the metadata is longer than 4294967295 bytes");
  }
  impl_ = std::make_unique<Impl>(path, body_count);
  std::array<char, kHeaderSize> header{};
  kMagic.copy(header.data(), kMagic.size());
  put_u32(&header[kVersionOffset], kRecordingVersion);
  put_u32(&header[kBodyCountOffset], body_count);
  put_u64(&header[kTimeStepOffset], std::bit_cast<std::uint64_t>(time_step));
  put_u32(&header[kFrameCountOffset], 0);  // finish() writes the count
  put_u32(&header[kMetadataLengthOffset], static_cast<std::uint32_t>(metadata.size()));
  std::ostream& out = impl_->file.stream();
  out.write(header.data(), header.size());
  out.write(metadata.data(), static_cast<std::streamsize>(metadata.size()));
  impl_->file.check_written();
}

RecordingWriter::~RecordingWriter() = default;

void RecordingWriter::add_frame(std::span<const BodyPose> poses) {
  const fs::path& path = impl_->file.path();
  if (impl_->finished) throw Error::in_file(path, "the recording is finished: no frame can follow");
  const std::uint32_t frame = impl_->frame_count;
  if (poses.size() != impl_->body_count) {
    throw Error::in_file(path, "frame " + std::to_string(frame) + " has " +
                                   std::to_string(poses.size()) + " poses, the recording has " +
                                   std::to_string(impl_->body_count) + " bodies");
  }
  if (frame == std::numeric_limits<std::uint32_t>::max()) {
    throw Error::in_file(path, "a recording holds at most 4294967295 frames");
  }
  // The frame is encoded whole before anything is written, so a refused frame leaves no trace.
  std::string& bytes = impl_->frame_bytes;
  bytes.resize(poses.size() * kPoseSize);
  for (std::size_t body = 0; body < poses.size(); ++body) {
    const PoseValues values = values_of(poses[body]);
    if (const auto problem = pose_problem(values)) {
      throw Error::in_file(path, "cannot record " + pose_place(frame, body) + *problem);
    }
    char* out = &bytes[body * kPoseSize];
    for (std::size_t k = 0; k < kPoseValues; ++k) {
      put_u32(out + 4 * k, std::bit_cast<std::uint32_t>(values[k]));
    }
  }
  impl_->file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  impl_->file.check_written();
  ++impl_->frame_count;
}

void RecordingWriter::finish() {
  if (impl_->finished)
    throw Error::in_file(impl_->file.path(), "the recording is already finished");
  std::array<char, 4> count{};
  put_u32(count.data(), impl_->frame_count);
  std::ostream& out = impl_->file.stream();
  out.seekp(static_cast<std::streamoff>(kFrameCountOffset));
  out.write(count.data(), count.size());
  impl_->file.commit();
  impl_->finished = true;
}

bool RecordingWriter::finished() const { return impl_->finished; }

std::span<const BodyPose> Recording::frame(std::uint32_t i) const {
  assert(i < frame_count);
  return std::span<const BodyPose>(poses).subspan(std::size_t{i} * body_count, body_count);
}

Recording read_recording(const fs::path& path) {
  InputFile file = open_input_file(path, InputKind::kRecording);
  std::ifstream& in = file.stream;
  const std::uint64_t file_size = file.size;

  if (file_size == 0) throw Error::in_file(path, "file is empty, not a sphys recording");
  std::array<char, kHeaderSize> header{};
  const auto header_bytes =
      static_cast<std::size_t>(std::min<std::uintmax_t>(file_size, kHeaderSize));
  read_exactly(in, header.data(), header_bytes, path);
  // A file shorter than the magic that starts like it is a truncated recording.
  const std::string_view magic(header.data(), std::min(header_bytes, kMagic.size()));
  if (magic != kMagic.substr(0, magic.size())) {
    throw Error::in_file(path, "not a sphys recording (it does not start with \"SPHYSREC\")");
  }
  const std::string truncated_header = "truncated header: the file has " +
                                       std::to_string(file_size) + " bytes, the header needs " +
                                       std::to_string(kHeaderSize);
  // The version is checked before the rest of the header: another version may lay it out
  // differently.
  if (header_bytes < kVersionOffset + 4) throw Error::in_file(path, truncated_header);
  const std::uint32_t version = get_u32(&header[kVersionOffset]);
  if (version != kRecordingVersion) {
    throw Error::in_file(path, "unsupported recording version " + std::to_string(version) +
                                   " (this build reads version " +
                                   std::to_string(kRecordingVersion) + ")");
  }
  if (header_bytes < kHeaderSize) throw Error::in_file(path, truncated_header);

  Recording recording;
  recording.version = version;
  recording.body_count = get_u32(&header[kBodyCountOffset]);
  recording.time_step = std::bit_cast<double>(get_u64(&header[kTimeStepOffset]));
  recording.frame_count = get_u32(&header[kFrameCountOffset]);
  const std::uint32_t metadata_length = get_u32(&header[kMetadataLengthOffset]);
  if (const auto problem = time_step_problem(recording.time_step)) {
    throw Error::in_file(path, *problem);
  }
  const std::uint64_t after_header = file_size - kHeaderSize;
  if (metadata_length > after_header) {
    throw Error::in_file(path, "truncated metadata: the header announces " +
                                   std::to_string(metadata_length) + " bytes, the file has " +
                                   std::to_string(after_header) + " after the header");
  }
  check_frames_size(path, recording.frame_count, recording.body_count,
                    after_header - metadata_length);

  recording.metadata.resize(metadata_length);
  read_exactly(in, recording.metadata.data(), metadata_length, path);
  // With no poses to read, a body count the file need not back must not size a frame buffer.
  if (recording.body_count == 0 || recording.frame_count == 0) return recording;

  recording.poses.resize(std::size_t{recording.frame_count} * recording.body_count);
  std::string bytes(std::size_t{recording.body_count} * kPoseSize, '\0');
  for (std::uint32_t frame = 0; frame < recording.frame_count; ++frame) {
    read_exactly(in, bytes.data(), bytes.size(), path);
    for (std::size_t body = 0; body < recording.body_count; ++body) {
      PoseValues values{};
      const char* pose_bytes = &bytes[body * kPoseSize];
      for (std::size_t k = 0; k < kPoseValues; ++k) {
        values[k] = std::bit_cast<float>(get_u32(pose_bytes + 4 * k));
      }
      if (const auto problem = pose_problem(values)) {
        throw Error::in_file(path, pose_place(frame, body) + *problem);
      }
      BodyPose& pose = recording.poses[std::size_t{frame} * recording.body_count + body];
      pose.position = Vec3(values[0], values[1], values[2]);
      pose.orientation = Quat(values[3], values[4], values[5], values[6]);
    }
  }
  return recording;
}

}  // namespace sphys::tools
