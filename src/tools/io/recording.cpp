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
#include <span>
#include <string>
#include <vector>

#include "atomic_file.h"
#include "input_file.h"
#include "sphys/error.h"
#include "sphys/world.h"

namespace sphys::tools {
namespace {

namespace fs = std::filesystem;

// The layout of docs/file-formats.md: magic, u32 version, u32 body count, f64 time step,
// u32 frame count, u32 metadata length; then the metadata, the joints (from version 2: a u32
// count and the records), then the frames.
constexpr std::string_view kMagic = "SPHYSREC";
constexpr std::size_t kVersionOffset = 8;
constexpr std::size_t kBodyCountOffset = 12;
constexpr std::size_t kTimeStepOffset = 16;
constexpr std::size_t kFrameCountOffset = 24;
constexpr std::size_t kMetadataLengthOffset = 28;
constexpr std::size_t kHeaderSize = 32;
// The first version that stores joints.
constexpr std::uint32_t kFirstVersionWithJoints = 2;

// A joint record: u32 type, u32 body a, u32 body b (kWorldBody for the world), then the anchors
// as 6 f32 (a's x y z, b's x y z).
constexpr std::size_t kJointCountSize = 4;
constexpr std::size_t kJointAnchorsOffset = 12;
constexpr std::size_t kJointSize = kJointAnchorsOffset + 6 * 4;
constexpr std::uint32_t kWorldBody = 0xFFFFFFFFu;
constexpr std::array<const char*, 5> kJointTypeNames = {"hinge", "slider", "ball", "weld",
                                                        "distance"};

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

std::uint32_t stored_body(const std::optional<std::uint32_t>& body) {
  return body ? *body : kWorldBody;
}

std::optional<std::uint32_t> body_of(std::uint32_t stored) {
  if (stored == kWorldBody) return std::nullopt;
  return stored;
}

std::string body_text(const std::optional<std::uint32_t>& body) {
  return body ? std::to_string(*body) : "the world";
}

// What is wrong with a joint, or nothing: what the writer refuses and the reader rejects.
std::optional<std::string> joint_problem(const RecordedJoint& joint, std::uint32_t body_count) {
  for (const auto& [name, body] : {std::pair{"body_a", joint.body_a}, {"body_b", joint.body_b}}) {
    if (body && *body >= body_count) {
      return std::string(name) + " " + std::to_string(*body) + " is not one of the " +
             std::to_string(body_count) + " bodies";
    }
  }
  if (joint.body_a == joint.body_b) {
    return "body_a and body_b are the same (" + body_text(joint.body_a) + ")";
  }
  for (const auto& [name, anchor] :
       {std::pair{"anchor_a", joint.anchor_a}, {"anchor_b", joint.anchor_b}}) {
    if (!anchor.allFinite()) {
      return std::string(name) + " is not finite (" + shown(anchor.x()) + " " + shown(anchor.y()) +
             " " + shown(anchor.z()) + ")";
    }
  }
  return std::nullopt;
}

std::string joint_place(std::size_t joint) { return "joint " + std::to_string(joint) + ": "; }

void put_joint(char* out, const RecordedJoint& joint) {
  put_u32(out, static_cast<std::uint32_t>(joint.type));
  put_u32(out + 4, stored_body(joint.body_a));
  put_u32(out + 8, stored_body(joint.body_b));
  for (int k = 0; k < 3; ++k) {
    put_u32(out + kJointAnchorsOffset + 4 * k, std::bit_cast<std::uint32_t>(joint.anchor_a[k]));
    put_u32(out + kJointAnchorsOffset + 12 + 4 * k,
            std::bit_cast<std::uint32_t>(joint.anchor_b[k]));
  }
}

// One joint record, checked; `where` names the joint in messages.
RecordedJoint get_joint(const char* in, std::uint32_t body_count, const fs::path& path,
                        const std::string& where) {
  const std::uint32_t type = get_u32(in);
  if (type >= kJointTypeNames.size()) {
    throw Error::in_file(path, where + "type " + std::to_string(type) +
                                   " is not a joint type (0 hinge, 1 slider, 2 ball, 3 weld, "
                                   "4 distance)");
  }
  RecordedJoint joint;
  joint.type = static_cast<JointType>(type);
  joint.body_a = body_of(get_u32(in + 4));
  joint.body_b = body_of(get_u32(in + 8));
  for (int k = 0; k < 3; ++k) {
    joint.anchor_a[k] = std::bit_cast<float>(get_u32(in + kJointAnchorsOffset + 4 * k));
    joint.anchor_b[k] = std::bit_cast<float>(get_u32(in + kJointAnchorsOffset + 12 + 4 * k));
  }
  if (const auto problem = joint_problem(joint, body_count)) {
    throw Error::in_file(path, where + kJointTypeNames[type] + ": " + *problem);
  }
  return joint;
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
// `available` counts the bytes after `before` (the metadata, or the joints).
void check_frames_size(const fs::path& path, std::uint32_t frame_count, std::uint32_t body_count,
                       std::uint64_t available, const std::string& before) {
  const std::uint64_t frame_size = std::uint64_t{body_count} * kPoseSize;
  const std::uint64_t whole_frames = frame_size == 0 ? frame_count : available / frame_size;
  if (whole_frames < frame_count) {
    throw Error::in_file(path, "truncated frames: only " + std::to_string(whole_frames) + " of " +
                                   std::to_string(frame_count) + " frames are whole; " +
                                   std::to_string(frame_count) + " frames of " +
                                   std::to_string(body_count) + " bodies need " +
                                   total_size_text(frame_count, frame_size) + " bytes after the " +
                                   before + ", the file has " + std::to_string(available));
  }
  const std::uint64_t expected = frame_count * frame_size;
  if (available > expected) {
    throw Error::in_file(path, std::to_string(available - expected) +
                                   " trailing bytes after the last frame (" +
                                   std::to_string(frame_count) + " frames of " +
                                   std::to_string(body_count) + " bodies)");
  }
}

// The joints after the metadata: their count, then the records, each checked, within the
// `available` bytes left in the file.
std::vector<RecordedJoint> read_joints(std::istream& in, const fs::path& path,
                                       std::uint32_t body_count, std::uint64_t available) {
  if (available < kJointCountSize) {
    throw Error::in_file(path,
                         "truncated joints: the joint count needs 4 bytes after the "
                         "metadata, the file has " +
                             std::to_string(available));
  }
  std::array<char, kJointCountSize> count_bytes{};
  read_exactly(in, count_bytes.data(), count_bytes.size(), path);
  const std::uint32_t count = get_u32(count_bytes.data());
  const std::uint64_t needed = std::uint64_t{count} * kJointSize;
  if (needed > available - kJointCountSize) {
    throw Error::in_file(path, "truncated joints: " + std::to_string(count) + " joints need " +
                                   std::to_string(needed) +
                                   " bytes after their count, the file "
                                   "has " +
                                   std::to_string(available - kJointCountSize));
  }
  std::vector<RecordedJoint> joints;
  joints.reserve(count);
  std::array<char, kJointSize> bytes{};
  for (std::uint32_t k = 0; k < count; ++k) {
    read_exactly(in, bytes.data(), bytes.size(), path);
    joints.push_back(get_joint(bytes.data(), body_count, path, joint_place(k)));
  }
  return joints;
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
                                 std::string_view metadata, std::span<const RecordedJoint> joints) {
  if (const auto problem = time_step_problem(time_step)) throw Error::in_file(path, *problem);
  if (metadata.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error::in_file(path, "the metadata is longer than 4294967295 bytes");
  }
  if (joints.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error::in_file(path, "a recording holds at most 4294967295 joints");
  }
  std::string joint_bytes(kJointCountSize + joints.size() * kJointSize, '\0');
  put_u32(joint_bytes.data(), static_cast<std::uint32_t>(joints.size()));
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (const auto problem = joint_problem(joints[k], body_count)) {
      throw Error::in_file(path, "cannot record " + joint_place(k) + *problem);
    }
    put_joint(&joint_bytes[kJointCountSize + k * kJointSize], joints[k]);
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
  out.write(joint_bytes.data(), static_cast<std::streamsize>(joint_bytes.size()));
  impl_->file.check_written();
}

RecordingWriter::~RecordingWriter() = default;

std::vector<BodyPose> recorded_poses(const World& world, std::span<const BodyId> bodies) {
  std::vector<BodyPose> poses;
  poses.reserve(bodies.size());
  for (const BodyId body : bodies) {
    const Transform& pose = world.body(body).pose;
    poses.push_back({pose.translation, pose.rotation});
  }
  return poses;
}

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
  if (version == 0 || version > kRecordingVersion) {
    throw Error::in_file(path, "unsupported recording version " + std::to_string(version) +
                                   " (this build reads versions 1 to " +
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
  recording.metadata.resize(metadata_length);
  read_exactly(in, recording.metadata.data(), metadata_length, path);
  std::uint64_t available = after_header - metadata_length;
  const bool has_joints = version >= kFirstVersionWithJoints;
  if (has_joints) {
    recording.joints = read_joints(in, path, recording.body_count, available);
    available -= kJointCountSize + recording.joints.size() * kJointSize;
  }
  check_frames_size(path, recording.frame_count, recording.body_count, available,
                    has_joints ? "joints" : "metadata");
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
