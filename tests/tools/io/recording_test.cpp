#include "sphys/tools/recording.h"

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <string_view>
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
using testing::EndsWith;
using testing::HasSubstr;
using testing::IsEmpty;
using testing::SizeIs;
using testing::StartsWith;

constexpr float kFloatNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kFloatInf = std::numeric_limits<float>::infinity();

// Little-endian bytes composed by hand from the layout in docs/file-formats.md, independent of
// the code under test.
class Bytes {
 public:
  Bytes& text(std::string_view s) {
    bytes_ += s;
    return *this;
  }
  Bytes& u32(std::uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes_ += static_cast<char>((value >> (8 * i)) & 0xff);
    return *this;
  }
  Bytes& u64(std::uint64_t value) {
    for (int i = 0; i < 8; ++i) bytes_ += static_cast<char>((value >> (8 * i)) & 0xff);
    return *this;
  }
  Bytes& f32(float value) { return u32(std::bit_cast<std::uint32_t>(value)); }
  Bytes& f64(double value) { return u64(std::bit_cast<std::uint64_t>(value)); }
  // Position x y z, orientation w x y z.
  Bytes& pose(float x, float y, float z, float qw, float qx, float qy, float qz) {
    return f32(x).f32(y).f32(z).f32(qw).f32(qx).f32(qy).f32(qz);
  }
  Bytes& header(std::uint32_t version, std::uint32_t body_count, double time_step,
                std::uint32_t frame_count, std::string_view metadata) {
    return text("SPHYSREC")
        .u32(version)
        .u32(body_count)
        .f64(time_step)
        .u32(frame_count)
        .u32(static_cast<std::uint32_t>(metadata.size()))
        .text(metadata);
  }
  // A joint record: type, body a, body b (0xFFFFFFFF: the world), anchor a, anchor b.
  Bytes& joint(std::uint32_t type, std::uint32_t body_a, std::uint32_t body_b, const Vec3& a,
               const Vec3& b) {
    u32(type).u32(body_a).u32(body_b);
    for (const Vec3& anchor : {a, b}) f32(anchor.x()).f32(anchor.y()).f32(anchor.z());
    return *this;
  }
  [[nodiscard]] const std::string& str() const { return bytes_; }

 private:
  std::string bytes_;
};

constexpr std::uint32_t kWorld = 0xFFFFFFFFu;

// The frames of valid_file().
Bytes& valid_frames(Bytes& bytes) {
  for (int frame = 0; frame < 3; ++frame) {
    bytes.pose(0, static_cast<float>(frame), 0, 1, 0, 0, 0).pose(1, 2, 3, 0, 0, 1, 0);
  }
  return bytes;
}

// A valid file of version 1 (no joints): 3 frames of 2 bodies, frames 1/60 s apart, metadata
// "{}".
Bytes valid_file() {
  Bytes bytes;
  bytes.header(1, 2, 1.0 / 60.0, 3, "{}");
  return valid_frames(bytes);
}

// The same in version 2 with one joint, a hinge from the world at (0, 1, 0) to body 1's
// (0.5, 0, 0), before the frames.
Bytes jointed_file(const Bytes& joints = Bytes().u32(1).joint(0, kWorld, 1, Vec3(0, 1, 0),
                                                              Vec3(0.5f, 0, 0))) {
  Bytes bytes;
  bytes.header(2, 2, 1.0 / 60.0, 3, "{}").text(joints.str());
  return valid_frames(bytes);
}

// The message of the Error that reading `path` throws.
std::string read_error(const fs::path& path) {
  try {
    (void)read_recording(path);
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no error reading " << path;
  return "";
}

// The message of the Error that reading a file of these bytes throws; it must name the file.
// The file goes to a scratch directory of its own: not for tests that hold a TempDir.
std::string bytes_error(const std::string& bytes) {
  const test::TempDir dir;
  const fs::path file = dir.write("bad.sphysrec", bytes);
  std::string message = read_error(file);
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  return message;
}

std::vector<std::uint32_t> bits_of(const BodyPose& pose) {
  const Quat& q = pose.orientation;
  std::vector<std::uint32_t> bits;
  for (const float value :
       {pose.position.x(), pose.position.y(), pose.position.z(), q.w(), q.x(), q.y(), q.z()}) {
    bits.push_back(std::bit_cast<std::uint32_t>(value));
  }
  return bits;
}

// Random poses with awkward values: tiny, huge, negative zero, and unit quaternions as a
// simulation leaves them (normalised in float, so not exactly of length 1).
std::vector<std::vector<BodyPose>> random_frames(std::uint32_t frames, std::uint32_t bodies) {
  std::mt19937 rng(20080316);
  std::uniform_real_distribution<float> coordinate(-1000.0f, 1000.0f);
  std::normal_distribution<float> component(0.0f, 1.0f);
  std::vector<std::vector<BodyPose>> result(frames);
  for (std::vector<BodyPose>& frame : result) {
    for (std::uint32_t body = 0; body < bodies; ++body) {
      BodyPose pose;
      pose.position = Vec3(coordinate(rng), coordinate(rng) * 1e-30f, coordinate(rng) * 1e30f);
      pose.orientation = Quat(component(rng), component(rng), component(rng), component(rng));
      pose.orientation.normalize();
      frame.push_back(pose);
    }
  }
  result[0][0].position =
      Vec3(-0.0f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max());
  return result;
}

TEST(Recording, RoundTripIsBitExact) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "run.sphysrec";
  const auto frames = random_frames(5, 7);
  RecordingWriter writer(file, 7, 0.004, "{\"scene\": 1}");
  for (const auto& frame : frames) writer.add_frame(frame);
  writer.finish();

  const Recording recording = read_recording(file);
  EXPECT_EQ(recording.version, 2u);
  EXPECT_THAT(recording.joints, IsEmpty());
  EXPECT_EQ(recording.time_step, 0.004);
  EXPECT_EQ(recording.metadata, "{\"scene\": 1}");
  EXPECT_EQ(recording.body_count, 7u);
  ASSERT_EQ(recording.frame_count, 5u);
  ASSERT_THAT(recording.poses, SizeIs(35));
  for (std::uint32_t f = 0; f < 5; ++f) {
    ASSERT_THAT(recording.frame(f), SizeIs(7));
    for (std::size_t b = 0; b < 7; ++b) {
      EXPECT_EQ(bits_of(recording.frame(f)[b]), bits_of(frames[f][b])) << f << " " << b;
    }
  }
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(Recording, BytesAreTheDocumentedLayout) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "run.sphysrec";
  const std::vector<RecordedJoint> joints = {
      {JointType::kHinge, std::nullopt, 1, Vec3(0, 1, 0), Vec3(0.5f, 0, 0)}};
  RecordingWriter writer(file, 2, 1.0 / 60.0, "{}", joints);
  for (int frame = 0; frame < 3; ++frame) {
    const std::vector<BodyPose> poses = {{Vec3(0, static_cast<float>(frame), 0), Quat(1, 0, 0, 0)},
                                         {Vec3(1, 2, 3), Quat(0, 0, 1, 0)}};
    writer.add_frame(poses);
  }
  writer.finish();
  EXPECT_EQ(read_whole(file), jointed_file().str());
}

// Every joint type, each way round with the world, comes back bit for bit.
TEST(Recording, RoundTripKeepsTheJoints) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "jointed.sphysrec";
  const std::vector<RecordedJoint> joints = {
      {JointType::kHinge, std::nullopt, 0, Vec3(0, 2, 0), Vec3(-0.5f, 0, 0)},
      {JointType::kSlider, 0, 1, Vec3::Zero(), Vec3(1e-30f, -0.0f, 3)},
      {JointType::kBall, 2, 1, Vec3(0.1f, 0.2f, 0.3f), Vec3::Zero()},
      {JointType::kWeld, 1, std::nullopt, Vec3(1, 1, 1), Vec3(-1, 0, 7)},
      {JointType::kDistance, 2, 0, Vec3::Zero(), Vec3(0, 0, 1)}};
  RecordingWriter writer(file, 3, 0.01, "{}", joints);
  writer.add_frame(random_frames(1, 3)[0]);
  writer.finish();
  const Recording recording = read_recording(file);
  EXPECT_EQ(recording.joints, joints);
  EXPECT_EQ(recording.frame_count, 1u);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(recording.joints[1].anchor_b.y()),
            std::bit_cast<std::uint32_t>(-0.0f));
}

// Recordings made before joints were kept (version 1) read as before, with no joints.
TEST(Recording, AVersionOneRecordingReadsWithNoJoints) {
  const test::TempDir dir;
  const Recording recording = read_recording(dir.write("old.sphysrec", valid_file().str()));
  EXPECT_EQ(recording.version, 1u);
  EXPECT_THAT(recording.joints, IsEmpty());
  ASSERT_EQ(recording.frame_count, 3u);
  EXPECT_EQ(recording.frame(2)[0].position.y(), 2.0f);
}

TEST(RecordingErrors, CorruptJoints) {
  const Vec3 zero = Vec3::Zero();
  const auto joint_error = [&](const Bytes& joints) {
    return bytes_error(jointed_file(joints).str());
  };
  EXPECT_THAT(joint_error(Bytes().u32(1).joint(9, kWorld, 1, zero, zero)),
              HasSubstr("joint 0: type 9 is not a joint type (0 hinge, 1 slider, 2 ball, 3 weld, "
                        "4 distance)"));
  EXPECT_THAT(joint_error(Bytes().u32(2).joint(2, 0, 1, zero, zero).joint(2, 0, 5, zero, zero)),
              HasSubstr("joint 1: ball: body_b 5 is not one of the 2 bodies"));
  EXPECT_THAT(joint_error(Bytes().u32(1).joint(3, 1, 1, zero, zero)),
              HasSubstr("joint 0: weld: body_a and body_b are the same (1)"));
  EXPECT_THAT(joint_error(Bytes().u32(1).joint(1, kWorld, kWorld, zero, zero)),
              HasSubstr("joint 0: slider: body_a and body_b are the same (the world)"));
  EXPECT_THAT(joint_error(Bytes().u32(1).joint(0, 0, 1, Vec3(0, kFloatNan, 0), zero)),
              HasSubstr("joint 0: hinge: anchor_a is not finite (0 nan 0)"));
  // A count the file does not back: 3 joints announced, one there, and no frames.
  Bytes cut;
  cut.header(2, 2, 0.01, 0, "{}").u32(3).joint(0, kWorld, 1, zero, zero);
  EXPECT_THAT(bytes_error(cut.str()),
              HasSubstr("truncated joints: 3 joints need 108 bytes after their count, the file "
                        "has 36"));
  Bytes no_count;
  no_count.header(2, 0, 0.01, 0, "{}").text("ab");
  EXPECT_THAT(bytes_error(no_count.str()),
              HasSubstr("truncated joints: the joint count needs 4 bytes after the metadata, the "
                        "file has 2"));
  // The frames after the joints are checked as after the metadata.
  const std::string whole = jointed_file().str();
  EXPECT_THAT(bytes_error(whole.substr(0, whole.size() - 1)),
              HasSubstr("only 2 of 3 frames are whole; 3 frames of 2 bodies need 168 bytes after "
                        "the joints, the file has 167"));
}

TEST(Recording, ReadsAHandWrittenFile) {
  const test::TempDir dir;
  const Recording recording = read_recording(dir.write("hand.sphysrec", valid_file().str()));
  EXPECT_EQ(recording.time_step, 1.0 / 60.0);
  EXPECT_EQ(recording.metadata, "{}");
  ASSERT_EQ(recording.frame_count, 3u);
  ASSERT_EQ(recording.body_count, 2u);
  EXPECT_EQ(recording.frame(2)[0].position, Vec3(0, 2, 0));
  EXPECT_EQ(recording.frame(2)[1].position, Vec3(1, 2, 3));
  EXPECT_EQ(recording.frame(2)[1].orientation.coeffs(), Quat(0, 0, 1, 0).coeffs());
}

TEST(Recording, MetadataIsKeptByteForByte) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "utf8.sphysrec";
  // Non-ASCII UTF-8 (2, 3 and 4 bytes per character) and a zero byte.
  const std::string metadata = "{\"name\": \"Kaninchen \xC3\xBC \xE5\x85\x94 \xF0\x9F\x90\x87\"}" +
                               std::string(1, '\0') + "end";
  RecordingWriter writer(file, 1, 0.01, metadata);
  writer.add_frame(std::vector<BodyPose>(1));
  writer.finish();
  const Recording recording = read_recording(file);
  EXPECT_EQ(recording.metadata, metadata);
  // The length field counts bytes, not characters.
  EXPECT_EQ(read_whole(file).substr(28, 4), Bytes().u32(37).str());
  EXPECT_EQ(metadata.size(), 37u);
}

TEST(Recording, EmptyRecording) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "empty.sphysrec";
  RecordingWriter writer(file, 3, 0.5, "");
  writer.finish();
  EXPECT_EQ(read_whole(file), Bytes().header(2, 3, 0.5, 0, "").u32(0).str());
  const Recording recording = read_recording(file);
  EXPECT_EQ(recording.body_count, 3u);
  EXPECT_EQ(recording.frame_count, 0u);
  EXPECT_THAT(recording.poses, IsEmpty());
  EXPECT_THAT(recording.metadata, IsEmpty());
}

TEST(Recording, FramesWithoutBodies) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "nobody.sphysrec";
  RecordingWriter writer(file, 0, 0.5, "{}");
  for (int i = 0; i < 4; ++i) writer.add_frame({});
  writer.finish();
  const Recording recording = read_recording(file);
  EXPECT_EQ(recording.frame_count, 4u);
  EXPECT_THAT(recording.frame(3), IsEmpty());
}

TEST(Recording, FramesAreStreamedToDiskNotHeld) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "big.sphysrec";
  constexpr std::uint32_t kBodies = 1000;
  constexpr std::uintmax_t kFrameSize = std::uintmax_t{kBodies} * 28;
  RecordingWriter writer(file, kBodies, 0.01, "{}");
  const std::vector<BodyPose> frame(kBodies);
  for (int i = 0; i < 10; ++i) writer.add_frame(frame);
  // Before finish() only the temporary exists, and it already holds (nearly) every frame.
  const std::vector<fs::path> files = files_in(dir.path());
  ASSERT_THAT(files, SizeIs(1));
  EXPECT_THAT(files[0].filename().string(), AllOf(StartsWith("big.sphysrec."), EndsWith(".tmp")));
  // The header, the metadata "{}", the joint count (no joints), the frames.
  EXPECT_GE(fs::file_size(files[0]), 32 + 2 + 4 + 9 * kFrameSize);
  writer.finish();
  EXPECT_EQ(fs::file_size(file), 32 + 2 + 4 + 10 * kFrameSize);
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(Recording, AbandonedWriterLeavesNothing) {
  const test::TempDir dir;
  {
    RecordingWriter writer(dir.path() / "abandoned.sphysrec", 2, 0.01, "{}");
    writer.add_frame(std::vector<BodyPose>(2));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(Recording, AbandonedWriterKeepsAnExistingFile) {
  const test::TempDir dir;
  const fs::path file = dir.write("old.sphysrec", "previous contents");
  {
    RecordingWriter writer(file, 2, 0.01, "{}");
    writer.add_frame(std::vector<BodyPose>(2));
  }
  EXPECT_EQ(read_whole(file), "previous contents");
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

TEST(Recording, FinishReplacesAnExistingFile) {
  const test::TempDir dir;
  const fs::path file = dir.write("old.sphysrec", std::string(100000, 'x'));
  RecordingWriter writer(file, 3, 0.5, "");
  writer.finish();
  EXPECT_EQ(read_whole(file), Bytes().header(2, 3, 0.5, 0, "").u32(0).str());
  EXPECT_THAT(files_in(dir.path()), ElementsAre(file));
}

// --- The writer refuses what the reader would reject, before writing anything. ---

// The message of the Error that add_frame(poses) throws on a writer of `bodies` bodies which has
// already recorded one frame; the writer must then still record a good frame.
std::string add_frame_error(std::uint32_t bodies, const std::vector<BodyPose>& poses) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "w.sphysrec";
  RecordingWriter writer(file, bodies, 0.01, "{}");
  writer.add_frame(std::vector<BodyPose>(bodies));
  std::string message;
  try {
    writer.add_frame(poses);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    message = error.what();
  }
  EXPECT_THAT(message, StartsWith(file.string() + ": "));
  writer.add_frame(std::vector<BodyPose>(bodies));
  writer.finish();
  EXPECT_EQ(read_recording(file).frame_count, 2u);
  return message;
}

TEST(RecordingWriter, WrongPoseCountThrows) {
  EXPECT_THAT(add_frame_error(3, std::vector<BodyPose>(2)),
              HasSubstr("frame 1 has 2 poses, the recording has 3 bodies"));
  EXPECT_THAT(add_frame_error(3, std::vector<BodyPose>(4)),
              HasSubstr("frame 1 has 4 poses, the recording has 3 bodies"));
}

TEST(RecordingWriter, NonFiniteValueThrows) {
  std::vector<BodyPose> poses(3);
  poses[2].position.y() = kFloatNan;
  EXPECT_THAT(add_frame_error(3, poses),
              HasSubstr("cannot record frame 1, body 2: position y is not finite (nan)"));
  poses[2].position.y() = 0;
  poses[0].orientation.w() = -kFloatInf;
  EXPECT_THAT(add_frame_error(3, poses),
              HasSubstr("frame 1, body 0: orientation w is not finite (-inf)"));
}

TEST(RecordingWriter, NonUnitOrientationThrows) {
  std::vector<BodyPose> poses(2);
  poses[1].orientation = Quat(0, 0, 2, 0);
  EXPECT_THAT(add_frame_error(2, poses),
              HasSubstr("frame 1, body 1: orientation has length 2, not 1"));
}

TEST(RecordingWriter, NothingFollowsFinish) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "w.sphysrec";
  RecordingWriter writer(file, 1, 0.01, "{}");
  writer.add_frame(std::vector<BodyPose>(1));
  EXPECT_FALSE(writer.finished());
  writer.finish();
  EXPECT_TRUE(writer.finished());
  EXPECT_THROW(
      {
        try {
          writer.add_frame(std::vector<BodyPose>(1));
        } catch (const Error& error) {
          EXPECT_EQ(std::string(error.what()),
                    file.string() + ": the recording is finished: no frame can follow");
          throw;
        }
      },
      Error);
  EXPECT_THROW(
      {
        try {
          writer.finish();
        } catch (const Error& error) {
          EXPECT_EQ(std::string(error.what()),
                    file.string() + ": the recording is already finished");
          throw;
        }
      },
      Error);
  // The finished file is left as it was: one frame.
  EXPECT_EQ(read_recording(file).frame_count, 1u);
}

TEST(RecordingWriter, BadTimeStepThrowsBeforeCreatingTheFile) {
  const test::TempDir dir;
  for (const double step : {0.0, -0.01, std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(RecordingWriter(dir.path() / "w.sphysrec", 1, step, ""), Error) << step;
  }
  try {
    RecordingWriter writer(dir.path() / "w.sphysrec", 1, -0.5, "");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("time step must be positive and finite, got -0.5 s"));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(RecordingWriter, BadJointThrowsBeforeCreatingTheFile) {
  const test::TempDir dir;
  const fs::path file = dir.path() / "w.sphysrec";
  const std::vector<RecordedJoint> joints = {
      {JointType::kBall, 0, std::nullopt, Vec3::Zero(), Vec3::Zero()},
      {JointType::kHinge, 0, 3, Vec3::Zero(), Vec3::Zero()}};
  try {
    RecordingWriter writer(file, 2, 0.01, "", joints);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(
        error.what(),
        HasSubstr(file.string() + ": cannot record joint 1: body_b 3 is not one of the 2 bodies"));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

TEST(RecordingWriter, MissingDirectoryThrows) {
  const test::TempDir dir;
  try {
    RecordingWriter writer(dir.path() / "absent" / "w.sphysrec", 1, 0.01, "");
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(),
                AllOf(HasSubstr("w.sphysrec: "), HasSubstr("the directory does not exist")));
  }
  EXPECT_THAT(files_in(dir.path()), IsEmpty());
}

// --- Corrupt files: every message names the file and the problem. ---

TEST(RecordingErrors, MissingFile) {
  const test::TempDir dir;
  EXPECT_THAT(read_error(dir.path() / "absent.sphysrec"),
              AllOf(HasSubstr("absent.sphysrec: "), HasSubstr("no such file")));
}

TEST(RecordingErrors, Directory) {
  const test::TempDir dir;
  EXPECT_THAT(read_error(dir.path()), HasSubstr("is a directory"));
}

TEST(RecordingErrors, EmptyFile) {
  EXPECT_THAT(bytes_error(std::string()), HasSubstr("file is empty, not a sphys recording"));
}

TEST(RecordingErrors, BadMagic) {
  std::string bytes = valid_file().str();
  bytes[5] = 'X';
  EXPECT_THAT(bytes_error(bytes), HasSubstr("not a sphys recording"));
  EXPECT_THAT(bytes_error("2 2\n0 0 0 1 1\n"), HasSubstr("not a sphys recording"));
  EXPECT_THAT(bytes_error("SPX"), HasSubstr("not a sphys recording"));
}

TEST(RecordingErrors, UnsupportedVersion) {
  Bytes bytes;
  bytes.header(3, 2, 0.01, 0, "");
  EXPECT_THAT(bytes_error(bytes.str()),
              HasSubstr("unsupported recording version 3 (this build reads versions 1 to 2)"));
  EXPECT_THAT(bytes_error(Bytes().header(0, 2, 0.01, 0, "").str()),
              HasSubstr("unsupported recording version 0"));
  // A version is read before the rest of the header, whose layout it may change.
  EXPECT_THAT(bytes_error(Bytes().text("SPHYSREC").u32(7).str()),
              HasSubstr("unsupported recording version 7"));
}

TEST(RecordingErrors, TruncatedHeader) {
  const std::string header = Bytes().header(1, 2, 0.01, 0, "").str();
  EXPECT_THAT(bytes_error(header.substr(0, 20)),
              HasSubstr("truncated header: the file has 20 bytes, the header needs 32"));
  EXPECT_THAT(bytes_error(header.substr(0, 31)), HasSubstr("truncated header"));
  EXPECT_THAT(bytes_error("SPHYS"), HasSubstr("truncated header: the file has 5 bytes"));
}

TEST(RecordingErrors, TruncatedMetadata) {
  const std::string bytes = Bytes().header(1, 2, 0.01, 0, "{\"scene\": 1}").str();
  EXPECT_THAT(bytes_error(bytes.substr(0, bytes.size() - 3)),
              HasSubstr("truncated metadata: the header announces 12 bytes, the file has 9 after "
                        "the header"));
}

TEST(RecordingErrors, TruncatedFrames) {
  // 3 frames of 2 bodies are 168 bytes; cut 10 bytes into the second frame.
  const std::string bytes = valid_file().str();
  const std::size_t frames_start = 32 + 2;
  EXPECT_THAT(bytes_error(bytes.substr(0, frames_start + 56 + 10)),
              HasSubstr("truncated frames: only 1 of 3 frames are whole; 3 frames of 2 bodies "
                        "need 168 bytes after the metadata, the file has 66"));
  EXPECT_THAT(bytes_error(bytes.substr(0, bytes.size() - 1)),
              HasSubstr("only 2 of 3 frames are whole"));
}

TEST(RecordingErrors, FrameCountBeyondAnyFile) {
  Bytes bytes;
  bytes.header(1, 0xffffffff, 0.01, 0xffffffff, "").pose(0, 0, 0, 1, 0, 0, 0);
  EXPECT_THAT(bytes_error(bytes.str()),
              AllOf(HasSubstr("only 0 of 4294967295 frames are whole"),
                    HasSubstr("need more than 18446744073709551615 bytes")));
}

TEST(RecordingErrors, TrailingBytes) {
  EXPECT_THAT(bytes_error(valid_file().str() + "extra"),
              HasSubstr("5 trailing bytes after the last frame (3 frames of 2 bodies)"));
  EXPECT_THAT(bytes_error(Bytes().header(1, 0, 0.01, 9, "").text("x").str()),
              HasSubstr("1 trailing bytes after the last frame (9 frames of 0 bodies)"));
}

TEST(RecordingErrors, NonFinitePoseValue) {
  Bytes bytes;
  bytes.header(1, 2, 0.01, 2, "");
  bytes.pose(0, 0, 0, 1, 0, 0, 0).pose(0, 0, 0, 1, 0, 0, 0);
  bytes.pose(0, 0, 0, 1, 0, 0, 0).pose(0, 0, 0, 1, kFloatNan, 0, 0);
  EXPECT_THAT(bytes_error(bytes.str()),
              HasSubstr("frame 1, body 1: orientation x is not finite (nan)"));

  Bytes infinite;
  infinite.header(1, 1, 0.01, 1, "").pose(0, 0, kFloatInf, 1, 0, 0, 0);
  EXPECT_THAT(bytes_error(infinite.str()),
              HasSubstr("frame 0, body 0: position z is not finite (inf)"));
}

TEST(RecordingErrors, TimeStepNotPositive) {
  EXPECT_THAT(bytes_error(Bytes().header(1, 0, 0.0, 0, "").str()),
              HasSubstr("time step must be positive and finite, got 0 s"));
  EXPECT_THAT(bytes_error(Bytes().header(1, 0, -1e-300, 0, "").str()), HasSubstr("got -1e-300 s"));
  EXPECT_THAT(
      bytes_error(Bytes().header(1, 0, std::numeric_limits<double>::quiet_NaN(), 0, "").str()),
      HasSubstr("time step must be positive and finite, got nan s"));
}

TEST(RecordingErrors, OrientationFarFromUnitLength) {
  Bytes bytes;
  bytes.header(1, 2, 0.01, 3, "");
  for (int frame = 0; frame < 2; ++frame) {
    bytes.pose(0, 0, 0, 1, 0, 0, 0).pose(0, 0, 0, 0, 0, 0, 1);
  }
  bytes.pose(0, 0, 0, 1, 0, 0, 0).pose(0, 0, 0, 0.5f, 0, 0, 0);
  EXPECT_THAT(bytes_error(bytes.str()),
              HasSubstr("frame 2, body 1: orientation has length 0.5, not 1"));

  Bytes zero;
  zero.header(1, 1, 0.01, 1, "").pose(0, 0, 0, 0, 0, 0, 0);
  EXPECT_THAT(bytes_error(zero.str()),
              HasSubstr("frame 0, body 0: orientation has length 0, not 1"));
}

TEST(RecordingErrors, OrientationNearUnitLengthIsAccepted) {
  // Within float rounding of a normalised quaternion, and a little beyond.
  const float almost = 1.0f + 1e-5f;
  Bytes bytes;
  bytes.header(1, 2, 0.01, 1, "").pose(0, 0, 0, almost, 0, 0, 0).pose(0, 0, 0, 0.6f, 0.8f, 0, 0);
  const test::TempDir dir;
  const Recording recording = read_recording(dir.write("near.sphysrec", bytes.str()));
  EXPECT_EQ(recording.frame(0)[0].orientation.w(), almost);
}

}  // namespace
}  // namespace sphys::tools
