// SPDX-License-Identifier: GPL-3.0-or-later
// The record of a run, typed: what Session::Finish returns and what the CLI, the mms physics
// tier, benchmarks and tests read. It becomes result.json only at the file boundary
// (RunRecordJson), whose keys docs/results.md describes.
#ifndef UNIMOUSE_RUN_RUN_RECORD_H_
#define UNIMOUSE_RUN_RUN_RECORD_H_

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kernel.h"
#include "real_time_pacer.h"
#include "result_record.h"
#include "scenario.h"
#include "world.h"

namespace unimouse {

/// The firmware link that drives a robot, as its components declared it.
struct LinkRecord {
  std::string transport;               ///< the spec's scheme (docs/results.md lists them)
  std::string spec;                    ///< the whole transport spec
  std::string profile;                 ///< what the firmware expects ("unimousesim-0.1")
  std::optional<FileRecord> firmware;  ///< none for a board's or a port's firmware
};

/// What drives a robot: a controller, a firmware over a link, both, or neither.
struct DriverRecord {
  std::optional<FileRecord> controller;
  std::optional<LinkRecord> link;
};

/// One robot of the run and what happened to it.
struct RobotRecord {
  std::string name;  ///< as sim.robots() gives it
  FileRecord file;   ///< its robot file
  DriverRecord driver;
  Pose2D pose;  ///< where it was when the run ended
  int64_t wall_contacts = 0;
  int64_t robot_contacts = 0;
  int64_t restarts = 0;  ///< times its firmware started over inside the run
};

/// The scenario of the run, its parameters and its verdict.
struct ScenarioRunRecord {
  std::string name;
  FileRecord file;
  std::map<std::string, ScenarioValue> params;
  ScenarioOutcome outcome;  ///< never "running": a run's end decides it
  std::vector<std::string> hud;
  std::string traceback;  ///< of a script error; "" none
};

/// What a viewer's window showed of a run.
struct ViewRecord {
  int64_t frames = 0;            ///< frames drawn
  double frames_per_second = 0;  ///< over the time from the first frame to the last
};

/// The record of one run.
struct RunRecord {
  std::string status;  ///< "completed", "fault" or "interrupted"
  std::string error;   ///< the fault or interruption; "" none
  int exit_code = 0;   ///< kExitPassed, kExitFailed or kExitRuntimeFault
  uint64_t seed = 0;
  double duration_s = 0;  ///< simulated seconds the run was given
  double sim_time_s = 0;  ///< simulated seconds it ran
  int64_t steps = 0;
  double wall_time_s = 0;
  double real_time_factor = 0;
  TickTimes wall_time_split;  ///< where the wall time went
  bool firmware_paced = false;
  int64_t collision_proxy_overflows = 0;
  std::string robot_name;           ///< the first robot file's `name`
  std::optional<MazeRecord> maze;   ///< none for a run without a maze
  std::vector<RobotRecord> robots;  ///< the first is the robot of a one-robot run
  std::optional<ScenarioRunRecord> scenario;
  std::optional<PacingReport> real_time_pacing;  ///< paced to the wall clock only
  int pictures_written = 0;
  std::string pictures_renderer;     ///< how they were drawn
  std::string pictures_unavailable;  ///< why none could be drawn; "" not asked or written
  bool firmware_maze = false;        ///< maze.png drawn from the firmware's reports
  /// What components measured over the run, by component and name.
  std::map<std::string, std::map<std::string, double>> measurements;
  std::optional<int64_t> restarts;  ///< all robots' firmware restarts, with a firmware only
  std::vector<Contact> contacts;    ///< every contact as it began, the first ContactWatch::kMaxKept
  int64_t contacts_not_kept = 0;    ///< contacts beyond those
  std::vector<std::string> warnings;  ///< every warning logged, "component: text"
  std::optional<ViewRecord> view;     ///< with a viewer only

  /// The first robot: the robot of a one-robot run.
  const RobotRecord& robot() const { return robots.front(); }
};

/// A contact as result.json's `contacts` and the recording's events hold it; `robot_names` by
/// robot index.
nlohmann::json ContactJson(const Contact& contact, const std::vector<std::string>& robot_names);

/// The record as result.json holds it (schema kResultSchemaVersion, docs/results.md).
nlohmann::json RunRecordJson(const RunRecord& record);

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_RUN_RECORD_H_
