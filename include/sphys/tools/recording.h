#pragma once

// Recordings: the pose of every body at every frame of a simulation, and the joints between them,
// kept for replay in a viewer and for export. The file (.sphysrec) is compact, little-endian
// binary with a version header, laid out byte by byte in docs/file-formats.md.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sphys/body_id.h"
#include "sphys/joint.h"
#include "sphys/math.h"

namespace sphys {
class World;
}  // namespace sphys

namespace sphys::tools {

// The format version this build writes. It reads this one and every earlier one: version 1 has
// no joints.
inline constexpr std::uint32_t kRecordingVersion = 2;

// Where one body is in one frame.
struct BodyPose {
  Vec3 position = Vec3::Zero();         // of the centre of mass. unit: m
  Quat orientation = Quat::Identity();  // body to world; unit length
};

// A joint as a recording keeps it: enough to draw it from the recorded body poses.
struct RecordedJoint {
  JointType type = JointType::kBall;  // what the joint leaves free
  // Indices into the recording's bodies; none: the world. Not both none, and not the same.
  std::optional<std::uint32_t> body_a;
  std::optional<std::uint32_t> body_b;  // as body_a
  Vec3 anchor_a = Vec3::Zero();         // in body a's frame (the world's for none). unit: m
  Vec3 anchor_b = Vec3::Zero();         // in body b's frame (the world's for none). unit: m
  // The same joint: every field equal.
  friend bool operator==(const RecordedJoint&, const RecordedJoint&) = default;
};

// The bodies' poses in `world` now, in the order given: one frame of a recording of them.
[[nodiscard]] std::vector<BodyPose> recorded_poses(const World& world,
                                                   std::span<const BodyId> bodies);

// Streams frames to disk as they come, so that a recording never has to fit in memory. The file
// appears at `path` only when finish() succeeds; until then the frames go to a temporary file next
// to it, which is removed if the writer is destroyed without finish() (an exception, a cancelled
// run). Every failure throws sphys::Error naming the file.
class RecordingWriter {
 public:
  // `time_step` is the time between frames (unit: s; positive and finite). `metadata` is stored
  // as given: the scene as JSON text, opaque to the recording. `joints` are stored before the
  // frames; a joint that names a body beyond `body_count`, the same body twice, the world twice,
  // or an anchor that is not finite throws before the file is created.
  RecordingWriter(const std::filesystem::path& path, std::uint32_t body_count, double time_step,
                  std::string_view metadata, std::span<const RecordedJoint> joints = {});
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // Appends one frame: a pose per body, in body order. Throws, writing nothing, when the number
  // of poses is not the body count, a value is not finite or an orientation is not of unit
  // length (what read_recording() would refuse), and after finish().
  void add_frame(std::span<const BodyPose> poses);
  // Stores the frame count in the header and moves the file into place, replacing an existing
  // one. Throws when called again.
  void finish();
  // True once finish() has succeeded: the file is in place.
  [[nodiscard]] bool finished() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A recording read whole (read_recording).
struct Recording {
  std::uint32_t version = kRecordingVersion;  // the file's format version
  double time_step = 0.0;                     // between frames. unit: s
  std::string metadata;                       // as the writer was given it: the scene as JSON
  std::uint32_t body_count = 0;               // poses per frame
  std::uint32_t frame_count = 0;              // frames recorded
  std::vector<BodyPose> poses;                // frame after frame, body_count poses each
  std::vector<RecordedJoint> joints;          // as the writer was given them; none in version 1

  // The poses of frame i (counting from 0; i < frame_count), in body order.
  [[nodiscard]] std::span<const BodyPose> frame(std::uint32_t i) const;
};

// Reads a whole recording, checking it: the header, the size against the counts it announces,
// every joint (its type, its bodies among the recording's, finite anchors) and every pose
// (finite, orientations of unit length). Throws sphys::Error naming the file and the problem
// (and the joint, or the frame and body, at fault).
[[nodiscard]] Recording read_recording(const std::filesystem::path& path);

}  // namespace sphys::tools
