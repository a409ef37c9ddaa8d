// SPDX-License-Identifier: GPL-3.0-or-later
// A run's recording, run.mcap, read by the tests' own MCAP reader (tests/support/mcap_reader.py,
// written from the specification, sharing nothing with the writer, which also checks every
// message against its channel's JSON Schema): the main job's poses are the trace's at the same
// times, its contest's goals are the result's runs at their times, its channels carry Foxglove's
// schema names, the files the run read are attached byte
// for byte, a crashed or killed run leaves a readable recording, and `--record` turns it off or
// asks for every step.
#include "run_recording.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "inline_assets.h"
#include "maze.h"
#include "mcap_json.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kFirmware = UNIMOUSE_FIRMWARE_DIR "/micromouse.so";

std::string SchemaOf(const json& recording, const std::string& topic) {
  for (const json& c : recording["channels"]) {
    if (c["topic"] != topic) continue;
    for (const json& s : recording["schemas"]) {
      if (s["id"] == c["schema_id"]) return s["name"];
    }
  }
  return "";
}

// trace.csv as rows of named numbers
std::vector<std::map<std::string, double>> ReadTrace(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> columns;
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) columns.push_back(c);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::stringstream cells(line);
    std::map<std::string, double> row;
    size_t i = 0;
    for (std::string cell; std::getline(cells, cell, ',') && i < columns.size(); ++i) {
      row[columns[i]] = std::stod(cell);
    }
    rows.push_back(row);
  }
  return rows;
}

uint64_t Nanoseconds(double time_s) { return static_cast<uint64_t>(std::llround(time_s * 1e9)); }

std::string OutDir(const std::string& name) { return (fs::temp_directory_path() / name).string(); }

double Yaw(const json& rotation) {
  return 2 * std::atan2(rotation["z"].get<double>(), rotation["w"].get<double>());
}

double AngleBetween(double a, double b) { return std::remainder(a - b, 2 * std::numbers::pi); }

TEST(RunRecordingTest, TheMainJobsPosesAreItsTracesAtTheSameTimes) {
  // the main job as the README runs it: the contest with the bundled racer firmware
  const testing::RunResult run = testing::UnimouseRun("--no-pictures", "main_job_record");
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const std::string out = OutDir("main_job_record");
  const json recording = testing::ReadRecording(out + "/run.mcap");
  ASSERT_TRUE(recording.is_object());
  EXPECT_TRUE(recording["complete"].get<bool>());
  EXPECT_EQ(SchemaOf(recording, "/robot/pose"), "foxglove.FrameTransform");

  // the trace (every 10 ms, the bundled robot's logger) is the independent truth
  std::map<uint64_t, json> poses;
  for (const json& m : testing::OnTopic(recording, "/robot/pose")) {
    ASSERT_EQ(m["data"]["parent_frame_id"], "world");
    ASSERT_EQ(m["data"]["timestamp"]["sec"].get<uint64_t>() * 1'000'000'000 +
                  m["data"]["timestamp"]["nsec"].get<uint64_t>(),
              m["log_time"].get<uint64_t>());
    poses[m["log_time"].get<uint64_t>()] = m["data"];
  }
  const auto trace = ReadTrace(out + "/trace.csv");
  ASSERT_GT(trace.size(), 1000u);
  for (const auto& row : trace) {
    const uint64_t time_ns = Nanoseconds(row.at("time_s"));
    ASSERT_TRUE(poses.contains(time_ns)) << "no pose at " << row.at("time_s") << " s";
    const json& pose = poses[time_ns];
    ASSERT_NEAR(pose["translation"]["x"].get<double>(), row.at("x_m"), 1e-9) << time_ns;
    ASSERT_NEAR(pose["translation"]["y"].get<double>(), row.at("y_m"), 1e-9) << time_ns;
    ASSERT_NEAR(AngleBetween(Yaw(pose["rotation"]), row.at("yaw_rad")), 0, 1e-9) << time_ns;
  }
  // at 100 Hz, as the trace: the recording's last pose is the end of the last step, which no
  // row of the trace sees
  EXPECT_LE(poses.size(), trace.size() + 1);

  // the log, the scenery once, the signals at 100 Hz, in Foxglove's schemas where there is one
  EXPECT_EQ(SchemaOf(recording, "/log"), "foxglove.Log");
  EXPECT_EQ(SchemaOf(recording, "/scenery"), "foxglove.SceneUpdate");
  EXPECT_EQ(SchemaOf(recording, "/signals"), "unimouse.Signals");
  ASSERT_EQ(testing::OnTopic(recording, "/scenery").size(), 1u);
  EXPECT_EQ(testing::OnTopic(recording, "/signals").size(), poses.size());
  EXPECT_GT(testing::OnTopic(recording, "/log").size(), 10u);

  // the scenery: one cube for each post and wall of the maze, and the maze's dimensions
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  size_t boxes = (maze.width() + 1) * (maze.height() + 1);
  for (int y = 0; y <= maze.height(); ++y) {
    for (int x = 0; x <= maze.width(); ++x) {
      boxes += (x < maze.width() && maze.HasHorizontalWall(x, y)) +
               (y < maze.height() && maze.HasVerticalWall(x, y));
    }
  }
  const json scenery = testing::OnTopic(recording, "/scenery")[0]["data"]["entities"][0];
  EXPECT_EQ(scenery["cubes"].size(), boxes);
  EXPECT_EQ(scenery["metadata"][2], json({{"key", "cell_m"}, {"value", "0.18"}}));

  // what the firmware believed, whenever it changed: at the end, the walls the scenario kept of
  // its reports (firmware_beliefs.json)
  EXPECT_EQ(SchemaOf(recording, "/beliefs"), "unimouse.Beliefs");
  const auto beliefs = testing::OnTopic(recording, "/beliefs");
  ASSERT_GT(beliefs.size(), 100u);
  EXPECT_EQ(beliefs.back()["data"]["walls"],
            json::parse(ReadTextFile(out + "/firmware_beliefs.json"))["walls"]);
  // never twice the same in a row, though the racer says again what it said at every cell
  for (size_t i = 1; i < beliefs.size(); ++i) {
    json now = beliefs[i]["data"], before = beliefs[i - 1]["data"];
    now.erase("timestamp");
    before.erase("timestamp");
    ASSERT_NE(now, before) << i;
  }
  // the HUD whenever it changed, never twice the same in a row
  const auto hud = testing::OnTopic(recording, "/hud");
  ASSERT_GT(hud.size(), 100u);
  for (size_t i = 1; i < hud.size(); ++i) {
    ASSERT_NE(hud[i]["data"]["lines"], hud[i - 1]["data"]["lines"]) << i;
  }

  // the last beliefs drawn for a 3D panel: a blue strip for each wall side the firmware knows
  // to be there, a tile for each visited cell
  const json last = json::parse(ReadTextFile(out + "/firmware_beliefs.json"));
  size_t strips = 0;
  for (const json& w : last["walls"]) {
    strips += std::popcount(static_cast<unsigned>(w[2].get<int>() & w[3].get<int>()));
  }
  const auto scenes = testing::OnTopic(recording, "/beliefs/scene");
  ASSERT_EQ(scenes.size(), beliefs.size());
  const json& drawn = scenes.back()["data"]["entities"][0];
  EXPECT_EQ(drawn["cubes"].size(), strips + beliefs.back()["data"]["visited"].size());
  EXPECT_EQ(drawn["lines"].size(), last["path"].size() > 1 ? 1u : 0u);

  // the three ToF beams every 30 ms, each starting at the robot's front corners, 7.7 cm from the
  // axle's middle where the trace has the robot
  EXPECT_EQ(SchemaOf(recording, "/beams"), "foxglove.SceneUpdate");
  const auto beams = testing::OnTopic(recording, "/beams");
  ASSERT_GT(beams.size(), 1000u);
  std::map<uint64_t, const std::map<std::string, double>*> row_at;
  for (const auto& row : trace) row_at[Nanoseconds(row.at("time_s"))] = &row;
  size_t checked = 0;
  for (size_t k = 0; k < beams.size(); ++k) {
    ASSERT_NEAR(beams[k]["log_time"].get<double>(), static_cast<double>(k) * 30e6, 1e3) << k;
    const json& points = beams[k]["data"]["entities"][0]["lines"][0]["points"];
    ASSERT_EQ(points.size(), 6u) << k;
    const auto row = row_at.find(beams[k]["log_time"].get<uint64_t>());
    if (row == row_at.end()) continue;
    for (size_t p = 0; p < 6; p += 2) {
      ASSERT_LT(std::hypot(points[p]["x"].get<double>() - row->second->at("x_m"),
                           points[p]["y"].get<double>() - row->second->at("y_m")),
                0.085)
          << k;
    }
    ++checked;
  }
  EXPECT_GT(checked, beams.size() / 4);

  // the contest's moments (sim.event in scenarios/micromouse.lua): a goal for each run that
  // result.json lists, in order, each at the time the result gives it (the run's start on the
  // contest clock plus its time) from the contest's start, the first run_start
  std::vector<std::pair<uint64_t, json>> goals, starts;
  for (const json& m : testing::OnTopic(recording, "/events")) {
    if (m["data"]["kind"] == "goal") goals.emplace_back(m["log_time"], m["data"]);
    if (m["data"]["kind"] == "run_start") starts.emplace_back(m["log_time"], m["data"]);
  }
  const json& runs = run.result["scenario"]["records"]["runs"];
  ASSERT_GT(runs.size(), 0u);
  ASSERT_EQ(runs.size(), run.result["scenario"]["scores"]["runs"].get<size_t>());
  ASSERT_EQ(goals.size(), runs.size());
  ASSERT_GE(starts.size(), runs.size());
  // the trace places each moment: the robot's cell at its rows just before and at or after it
  const auto cells_around = [&](uint64_t time_ns) {
    const auto cell = [](const std::map<std::string, double>& row) {
      return Cell{static_cast<int>(std::floor(row.at("x_m") / 0.18)),
                  static_cast<int>(std::floor(row.at("y_m") / 0.18))};
    };
    size_t after = 0;
    while (after < trace.size() && Nanoseconds(trace[after].at("time_s")) < time_ns) ++after;
    EXPECT_GT(after, 0u);
    EXPECT_LT(after, trace.size());
    after = std::clamp<size_t>(after, 1, trace.size() - 1);
    return std::pair{cell(trace[after - 1]), cell(trace[after])};
  };
  const auto is_goal = [&](Cell c) {
    return std::find(maze.goals().begin(), maze.goals().end(), c) != maze.goals().end();
  };
  // the contest starts as the robot's centre leaves the start cell
  const uint64_t contest_ns = starts[0].first;
  const auto [before_start, after_start] = cells_around(contest_ns);
  EXPECT_EQ(before_start, maze.start());
  EXPECT_NE(after_start, maze.start());
  uint64_t last_ns = contest_ns;
  for (size_t i = 0; i < runs.size(); ++i) {
    const double at_s =
        runs[i]["start_s"].get<double>() + runs[i]["time_s"].get<double>() + contest_ns * 1e-9;
    EXPECT_NEAR(goals[i].first * 1e-9, at_s, 0.0005) << "run " << i + 1;
    EXPECT_GT(goals[i].first, last_ns) << "run " << i + 1;
    last_ns = goals[i].first;
    // a run that skipped a cell has no path cost
    const std::string cost =
        runs[i].contains("path_cost") ? std::to_string(runs[i]["path_cost"].get<int>()) : "unknown";
    char text[96];
    std::snprintf(text, sizeof(text), "run %zu: %.3f s, path cost %s", i + 1,
                  runs[i]["time_s"].get<double>(), cost.c_str());
    EXPECT_EQ(goals[i].second["text"], text);
    // the goal is the moment the robot's centre enters a goal cell
    const auto [before, after] = cells_around(goals[i].first);
    EXPECT_FALSE(is_goal(before)) << "run " << i + 1;
    EXPECT_TRUE(is_goal(after)) << "run " << i + 1;
  }
}

TEST(RunRecordingTest, ContactsAndTheMomentAMouseIsLostAreEventsAsTheResultListsThem) {
  // the micromouse example loses its position in Portugal 2024's final maze at 65.6 s, after
  // touching walls (ResultRecordTest.TheMomentTheExampleMouseLosesItsPositionIsAWarning)
  const std::string shared = testing::SharedMazesDir();
  if (shared.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  const testing::RunResult run =
      testing::UnimouseRun("--scenario micromouse --link inproc:" + kFirmware + " --maze " +
                               shared + "/classic/Portugal-2024-Final.txt --duration 70",
                           "lost_record");
  ASSERT_EQ(run.outcome.exit_code, 1) << run.outcome.output;
  const json recording = testing::ReadRecording(OutDir("lost_record") + "/run.mcap");
  ASSERT_TRUE(recording.is_object());
  EXPECT_EQ(SchemaOf(recording, "/events"), "unimouse.Event");
  std::vector<json> contacts, lost;
  for (const json& m : testing::OnTopic(recording, "/events")) {
    // the run's own kinds; the contest's events (sim.event) are another test's
    if (m["data"]["kind"] == "contact") contacts.push_back(m["data"]);
    if (m["data"]["kind"] == "lost") lost.push_back(m["data"]);
  }
  // every contact of result.json, with the same facts, at its time
  const json& listed = run.result["contacts"];
  ASSERT_GT(listed.size(), 0u);
  ASSERT_EQ(contacts.size(), listed.size());
  for (size_t i = 0; i < contacts.size(); ++i) {
    EXPECT_EQ(contacts[i]["data"], listed[i]);
    EXPECT_EQ(contacts[i]["robot"], "unimouse");
  }
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0]["kind"], "lost");
  EXPECT_EQ(lost[0]["data"]["reported_cell"], json({11, 11}));
  EXPECT_EQ(lost[0]["data"]["true_cell"], json({11, 9}));
  EXPECT_EQ(lost[0]["timestamp"]["sec"], 65);
}

TEST(RunRecordingTest, AttachesTheFilesTheRunReadAndSaysWhatRan) {
  const testing::RunResult run = testing::UnimouseRun(
      "--scenario micromouse --link inproc:" + kFirmware + " --duration 0.3", "record_files");
  ASSERT_EQ(run.outcome.exit_code, 1) << run.outcome.output;  // no run finished in 0.3 s
  const std::string out = OutDir("record_files");
  const json recording = testing::ReadRecording(out + "/run.mcap");
  ASSERT_TRUE(recording.is_object());

  std::map<std::string, std::string> attached;
  for (const json& a : recording["attachments"]) attached[a["name"]] = a.value("data", "");
  EXPECT_EQ(attached["result.json"].empty(), false);
  EXPECT_EQ(json::parse(attached["result.json"]), json::parse(ReadTextFile(out + "/result.json")));
  const std::string robot = run.result["robots"][0]["file"];
  EXPECT_EQ(attached[fs::path(robot).filename().string()], ReadTextFile(robot));
  const std::string scenario = run.result["scenario"]["file"];
  EXPECT_EQ(attached[fs::path(scenario).filename().string()], ReadTextFile(scenario));
  const std::string maze = run.result["maze"];
  EXPECT_EQ(attached[fs::path(maze).filename().string()], ReadTextFile(maze));

  // the format first, which robot file is which, and at the end what ran
  ASSERT_EQ(recording["metadata"].size(), 3u);
  EXPECT_EQ(recording["metadata"][0]["name"], "unimouse.recording");
  EXPECT_EQ(recording["metadata"][0]["metadata"], json({{"format", "1"}}));
  EXPECT_EQ(recording["metadata"][1]["name"], "unimouse.robots");
  EXPECT_EQ(recording["metadata"][1]["metadata"],
            json({{"0.file", fs::path(robot).filename().string()}, {"0.name", "unimouse"}}));
  const json& identity = recording["metadata"][2]["metadata"];
  EXPECT_EQ(recording["metadata"][2]["name"], "unimouse.run");
  EXPECT_EQ(identity["seed"], "1");
  EXPECT_EQ(identity["unimouse_version"], run.result["unimouse_version"]);
  EXPECT_EQ(identity["robot_sha256"], run.result["robots"][0]["sha256"]);
  EXPECT_EQ(identity["scenario_sha256"], run.result["scenario"]["sha256"]);
  EXPECT_EQ(identity["maze_sha256"], run.result["maze_sha256"]);
}

TEST(RunRecordingTest, FullRecordsEveryStepAndOffRecordsNothing) {
  const std::string args = "--scenario micromouse --link inproc:" + kFirmware + " --duration 0.2";
  const testing::RunResult full = testing::UnimouseRun(args + " --record full", "record_full");
  ASSERT_EQ(full.outcome.exit_code, 1) << full.outcome.output;
  const json recording = testing::ReadRecording(OutDir("record_full") + "/run.mcap");
  ASSERT_TRUE(recording.is_object());
  // time 0, then the end of each of the 200 steps of 1 ms
  const auto poses = testing::OnTopic(recording, "/robot/pose");
  ASSERT_EQ(poses.size(), 201u);
  for (size_t k = 0; k < poses.size(); ++k) {
    ASSERT_NEAR(poses[k]["log_time"].get<double>(), static_cast<double>(k) * 1e6, 1e3) << k;
  }

  const testing::RunResult off = testing::UnimouseRun(args + " --record off", "record_off");
  ASSERT_EQ(off.outcome.exit_code, 1) << off.outcome.output;
  EXPECT_FALSE(fs::exists(OutDir("record_off") + "/run.mcap"));
  EXPECT_TRUE(fs::exists(OutDir("record_off") + "/result.json"));
}

TEST(RunRecordingTest, AFirmwareCrashLeavesACompleteRecordingOfEachRobot) {
  const testing::RunResult r = testing::UnimouseRun(
      "--maze japan2018 --scenario none --duration 1 --no-pictures --robot unimouse --link "
      "inproc:" +
          kFirmware + " --robot unimouse --name crasher --start 15,15,S --link inproc:" +
          UNIMOUSE_TEST_BINARY_DIR "/null_pointer_firmware.so",
      "record_crash");
  ASSERT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  const json recording = testing::ReadRecording(OutDir("record_crash") + "/run.mcap");
  ASSERT_TRUE(recording.is_object());
  EXPECT_TRUE(recording["complete"].get<bool>());
  // each robot its own frame, up to the step that faulted at 0.2 s
  for (const std::string name : {"unimouse", "crasher"}) {
    const auto poses = testing::OnTopic(recording, "/robots/" + name + "/pose");
    ASSERT_GE(poses.size(), 20u) << name;
    EXPECT_EQ(poses.back()["data"]["child_frame_id"], name);
    EXPECT_NEAR(poses.back()["log_time"].get<double>() * 1e-9, 0.2, 0.011) << name;
  }
  std::string result;
  for (const json& a : recording["attachments"]) {
    if (a["name"] == "result.json") result = a["data"];
  }
  EXPECT_EQ(json::parse(result)["status"], "fault");
}

TEST(RunRecordingTest, AKilledRunLeavesARecordingThatReadsToItsLastWholeChunk) {
  // killed outright, as by the OOM killer or a lost machine: no finish, no result. The contest
  // runs to its 10-minute limit here, some seconds after the kill
  const testing::RunResult r = testing::UnimouseRun(
      "--scenario micromouse --link inproc:" + kFirmware, "record_killed", "timeout -s KILL 3 ");
  ASSERT_EQ(r.outcome.exit_code, 128 + 9) << r.outcome.output;
  const json recording =
      testing::ReadRecording(OutDir("record_killed") + "/run.mcap", /*cut_ok=*/true);
  ASSERT_TRUE(recording.is_object());
  EXPECT_FALSE(recording["complete"].get<bool>());
  // every 10 ms from 0 (sim time, within its rounding to nanoseconds), at least a second of
  // them: a chunk is written out every second
  const auto poses = testing::OnTopic(recording, "/robot/pose");
  ASSERT_GE(poses.size(), 100u);
  for (size_t k = 0; k < poses.size(); ++k) {
    ASSERT_NEAR(poses[k]["log_time"].get<double>(), static_cast<double>(k) * 10e6, 1e3) << k;
  }
}

TEST(RunRecordingTest, ParsesItsThreeLevels) {
  EXPECT_EQ(ParseRecordLevel("off"), RecordLevel::kOff);
  EXPECT_EQ(ParseRecordLevel("light"), RecordLevel::kLight);
  EXPECT_EQ(ParseRecordLevel("full"), RecordLevel::kFull);
  EXPECT_THROW(ParseRecordLevel("Full"), InputError);
}

TEST(RunRecordingTest, AnUnknownLevelIsBadInput) {
  const testing::RunResult run =
      testing::UnimouseRun("--duration 0.1 --record sometimes", "record_unknown");
  EXPECT_EQ(run.outcome.exit_code, 2) << run.outcome.output;
  EXPECT_NE(run.outcome.output.find("--record sometimes: give off, light or full"),
            std::string::npos)
      << run.outcome.output;
}

}  // namespace
}  // namespace unimouse
