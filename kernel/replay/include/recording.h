// SPDX-License-Identifier: GPL-3.0-or-later
// A run's recording (run.mcap, docs/replay.md) read back into memory for a player: each robot's
// poses, the signals, the events, the log, what the firmware believed and reported, the HUD and
// the files the run read, all on the run's simulated time. A player re-simulates nothing: what
// it shows comes from here.
#ifndef UNIMOUSE_REPLAY_RECORDING_H_
#define UNIMOUSE_REPLAY_RECORDING_H_

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware_beliefs.h"
#include "maze.h"
#include "world.h"

namespace unimouse {

/// Something that happened at a time.
template <typename T>
struct Timed {
  double t_s = 0;
  T value;
};

/// A robot's path: its poses in time order.
struct RecordedRobot {
  std::string name;  ///< "" for the only robot of a run
  std::string file;  ///< the name of the attachment holding its robot file ("" when unknown)
  std::vector<Timed<Pose2D>> poses;
};

/// An event of /events: a contact, a lost position.
struct RecordedEvent {
  double t_s = 0;
  std::string kind;
  std::string robot;
  std::string text;
};

/// A line of /log, with Foxglove's level (1 debug, 2 info, 3 warning, 4 error).
struct RecordedLogLine {
  double t_s = 0;
  int level = 2;
  std::string name;
  std::string message;
};

struct Recording {
  std::string path;
  /// "" for a recording read to its end; otherwise a sentence saying where it was cut short.
  std::string cut_short;
  std::vector<RecordedRobot> robots;
  std::vector<StaticBox> scenery;
  std::optional<MazeDimensions> maze;  ///< the maze's dimensions, when the run had one
  int maze_width_cells = 0;
  int maze_height_cells = 0;
  std::vector<std::string> signal_names;
  std::vector<double> signal_times_s;
  std::vector<std::vector<double>> signal_rows;  ///< one per time, NaN where a value is null
  std::vector<RecordedEvent> events;
  std::vector<RecordedLogLine> log;
  std::vector<Timed<FirmwareBeliefs>> beliefs;  ///< colours as the letters mms uses
  std::vector<Timed<std::vector<std::string>>> hud;
  /// the firmware's reported values, by robot name
  std::map<std::string, std::vector<Timed<std::map<std::string, double>>>> firmware_values;
  std::map<std::string, std::string> attachments;   ///< by name
  std::map<std::string, std::string> run_metadata;  ///< unimouse.run: version, seed, hashes
  double end_s = 0;                                 ///< the last time it holds

  /// The index of the last entry of `times` at or before `t_s`, or -1.
  template <typename T>
  static int Latest(const std::vector<Timed<T>>& entries, double t_s);
};

/// A path's pose at `t_s`: between two samples, the straight line between them (the heading
/// turning the short way); before the first or after the last, that one. Needs a pose.
Pose2D PoseAt(const RecordedRobot& robot, double t_s);

/// Reads `path`: a run.mcap, or an output folder holding one. Throws InputError (exit code 2)
/// with one sentence for a file that is missing, empty, not MCAP, of a newer MCAP version or a
/// newer recording format, or not a unimouse recording; a recording cut short is read up to its
/// last whole record, saying so in `cut_short`.
Recording ReadRecording(const std::string& path);
/// Whether reading a recording reads a topic's messages: the others (the ToF beams, which a
/// replay draws from the signals, and the beliefs' 3D scene, which it draws from /beliefs) are
/// skipped without being parsed, most of a recording's JSON.
bool ReplayReadsTopic(const std::string& topic);
/// The same for a recording's bytes, named `name` (fuzzing, tests).
Recording ParseRecording(std::string_view bytes, const std::string& name);

template <typename T>
int Recording::Latest(const std::vector<Timed<T>>& entries, double t_s) {
  int lo = 0, hi = static_cast<int>(entries.size());  // the first entry after t_s is in [lo, hi]
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (entries[mid].t_s <= t_s) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo - 1;
}

}  // namespace unimouse

#endif  // UNIMOUSE_REPLAY_RECORDING_H_
