// SPDX-License-Identifier: GPL-3.0-or-later
// The recording of a run, run.mcap in its output folder (docs/replay.md): JSON messages, each
// channel with its JSON Schema, the 3D ones in Foxglove's published schemas so that Foxglove,
// Lichtblick and PlotJuggler show them as they are. Session feeds it what the run already has
// (poses, signals, the log) at its step boundaries; plugins never write it. Its chunks reach the
// disk at least every simulated second, so a run that dies leaves a recording that reads up to
// then.
#ifndef UNIMOUSE_RUN_RUN_RECORDING_H_
#define UNIMOUSE_RUN_RUN_RECORDING_H_

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "firmware_beliefs.h"
#include "kernel.h"

namespace unimouse {

class McapWriter;

/// How much of a run its recording holds.
enum class RecordLevel {
  kOff,    ///< no recording
  kLight,  ///< poses and signals at 100 Hz, the log, the maze
  kFull,   ///< poses and signals at every step, the log, the maze
};

/// Parses `--record`'s value: "off", "light" or "full"; throws InputError otherwise.
RecordLevel ParseRecordLevel(const std::string& text);

/// Seconds between two samples of poses and signals at kLight.
inline constexpr double kLightRecordPeriod_s = 0.01;

/// Seconds between two records of the ToF beams: a ToF sensor's period, at both levels.
inline constexpr double kBeamRecordPeriod_s = 0.03;

/// The version of what a recording holds (its channels and their messages), in its metadata
/// `unimouse.recording`: a player refuses a recording of a later one.
inline constexpr int kRecordingFormat = 1;

/// A run's recording, open from before its first step to after its result.
class RunRecording {
 public:
  /// Creates the file at `path` (throws InputError when it cannot).
  RunRecording(const std::string& path, RecordLevel level);
  /// Closes the file as Close() does, dropping an error.
  ~RunRecording();
  RunRecording(const RunRecording&) = delete;
  RunRecording& operator=(const RunRecording&) = delete;

  /// Records every robot's pose and every signal at the kernel's present time, when a sample is
  /// due there (every step at kFull, every 10 ms at kLight), and returns whether it was. The
  /// first call also records the world's scenery, once.
  bool Sample(const Kernel& kernel);
  /// Records what a robot's firmware believes about the maze, whole (call it when it changed;
  /// a snapshot the same as the robot's last one is left out).
  void Beliefs(double time_s, const std::string& robot, const FirmwareBeliefs& beliefs);
  /// Records the scenario's HUD lines (call it when they changed).
  void Hud(double time_s, const std::vector<std::string>& lines);
  /// Records the latest of each value a robot's firmware reported (call it when one changed).
  void FirmwareValues(double time_s, const std::string& robot,
                      const std::map<std::string, double>& values);
  /// Records an event at `time_s` on /events, for a replay to jump to: its kind (the run's own
  /// "contact" and "lost", or a scenario's word), the robot it happened to ("" none), a sentence,
  /// and its facts as a JSON object.
  void Event(double time_s, const std::string& kind, const std::string& robot,
             const std::string& text, const std::string& data_json);
  /// Records a line of the run's log (a UNIMOUSE_LOG_* level) at `time_s`.
  void Log(double time_s, int level, const std::string& component, const std::string& message);
  /// Attaches a file read from `path` under `name`, stamped `time_s`; a file that cannot be
  /// read is left out, returning false.
  bool AttachFile(const std::string& name, const std::string& path, const std::string& media_type,
                  double time_s);
  /// Attaches `content` under `name`, stamped `time_s`.
  void Attach(const std::string& name, const std::string& content, const std::string& media_type,
              double time_s);
  /// Adds a named set of key-value pairs (the version, seed, hashes).
  void AddMetadata(const std::string& name, const std::map<std::string, std::string>& values);
  /// Ends the recording: the summary and indexes that make it quick to open.
  void Close();

 private:
  void OpenRobotChannels(const Kernel& kernel);

  std::unique_ptr<McapWriter> writer_;
  RecordLevel level_;
  uint16_t frame_transform_schema_ = 0;
  uint16_t log_channel_ = 0;
  uint16_t events_channel_ = 0;
  uint16_t signals_channel_ = 0;
  uint16_t beliefs_channel_ = 0;
  uint16_t hud_channel_ = 0;
  uint16_t values_channel_ = 0;
  uint16_t beams_channel_ = 0;
  uint16_t beliefs_scene_channel_ = 0;
  std::map<std::string, std::string> last_beliefs_;  // by robot, the last snapshot unstamped
  std::optional<MazeDimensions> maze_dimensions_;    // with a maze, where its cells are
  int64_t beam_every_steps_ = 0;                     // 0: the robots have no beams
  std::vector<uint16_t> pose_channels_;
  std::vector<std::string> frame_names_;  // as JSON strings
  std::vector<std::string> signal_keys_;  // "name": of each signal, as JSON
  std::string message_;                   // the message being written, its memory kept
  int64_t sample_every_steps_ = 0;        // 0 until the first sample knows the step
};

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_RUN_RECORDING_H_
