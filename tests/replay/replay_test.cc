// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse replay` on real runs: a recording read back as its run's trace has it, two runs
// compared where their traces first part, a logged run (the trace itself, the sysid sketch's
// encoder log) beside the simulation, recordings cut short or not recordings at all, and the
// window under a virtual X server showing the robot where the recording puts it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "imported_run.h"
#include "mcap_reader.h"
#include "mcap_writer.h"
#include "png_file.h"
#include "recording.h"
#include "run_comparison.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kFirmware = UNIMOUSE_FIRMWARE_DIR "/micromouse.so";

struct TraceRow {
  double t_s, x_m, y_m, yaw_rad;
};

// trace.csv's first four columns (time_s, x_m, y_m, yaw_rad)
std::vector<TraceRow> ReadTrace(const std::string& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("time_s,x_m,y_m,yaw_rad,", 0), 0u) << line;
  std::vector<TraceRow> rows;
  while (std::getline(in, line)) {
    TraceRow row{};
    char comma = 0;
    std::istringstream cells(line);
    cells >> row.t_s >> comma >> row.x_m >> comma >> row.y_m >> comma >> row.yaw_rad;
    rows.push_back(row);
  }
  return rows;
}

// one column of trace.csv, by the row's time in milliseconds
std::map<int64_t, double> ReadTraceColumn(const std::string& file, const std::string& name) {
  std::ifstream in(file);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream header(line);
  size_t column = 0;
  while (std::getline(header, cell, ',') && cell != name) ++column;
  std::map<int64_t, double> values;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::vector<std::string> row;
    while (std::getline(cells, cell, ',')) row.push_back(cell);
    if (column < row.size())
      values[std::llround(std::stod(row[0]) * 1000)] = std::stod(row[column]);
  }
  return values;
}

std::string OutDir(const std::string& name) { return (fs::temp_directory_path() / name).string(); }

// the main job's first minute, recorded, once for the tests that only read it
class ReplayCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const testing::RunResult run = testing::UnimouseRun(
        "--scenario micromouse --link inproc:" + kFirmware + " --duration 60", "replay_main");
    ASSERT_EQ(run.outcome.exit_code, 1) << run.outcome.output;  // no run finished in a minute
  }
  static std::string Main() { return OutDir("replay_main"); }
};

TEST_F(ReplayCommandTest, ARecordingReadsBackAsItsRunsTraceHasIt) {
  const Recording r = ReadRecording(Main());
  EXPECT_EQ(r.path, Main() + "/run.mcap");
  EXPECT_EQ(r.cut_short, "");
  ASSERT_EQ(r.robots.size(), 1u);
  EXPECT_EQ(r.robots[0].file, "unimouse.yaml");
  // the trace is the truth: a pose at each of its times, equal to its
  const std::vector<TraceRow> trace = ReadTrace(Main() + "/trace.csv");
  ASSERT_GT(trace.size(), 5000u);
  const auto& poses = r.robots[0].poses;
  ASSERT_GE(poses.size(), trace.size());
  for (size_t i = 0; i < trace.size(); ++i) {
    ASSERT_NEAR(poses[i].t_s, trace[i].t_s, 1e-9) << i;
    ASSERT_NEAR(poses[i].value.x_m, trace[i].x_m, 1e-9) << i;
    ASSERT_NEAR(poses[i].value.y_m, trace[i].y_m, 1e-9) << i;
    ASSERT_NEAR(std::remainder(poses[i].value.yaw_rad - trace[i].yaw_rad, 2 * std::numbers::pi), 0,
                1e-9)
        << i;
    // between two samples, halfway
    if (i + 1 < trace.size()) {
      const Pose2D half = PoseAt(r.robots[0], (trace[i].t_s + trace[i + 1].t_s) / 2);
      ASSERT_NEAR(half.x_m, (trace[i].x_m + trace[i + 1].x_m) / 2, 1e-9) << i;
    }
  }
  EXPECT_NEAR(r.end_s, 60, 1e-6);
  // the maze's 289 posts and its walls, its cells of 18 cm; the robot file as the run read it
  ASSERT_TRUE(r.maze.has_value());
  EXPECT_EQ(r.maze->cell_m, 0.18);
  EXPECT_EQ(r.maze_width_cells, 16);
  int posts = 0;
  for (const StaticBox& box : r.scenery) posts += box.kind == StaticBox::Kind::kPost;
  EXPECT_EQ(posts, 17 * 17);
  EXPECT_EQ(r.attachments.at("unimouse.yaml"),
            ReadTextFile(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml"));
  // the signals at the trace's times: the left motor's voltage as the trace has it
  ASSERT_EQ(r.signal_times_s.size(), poses.size());
  EXPECT_NE(std::find(r.signal_names.begin(), r.signal_names.end(), "left.voltage_v"),
            r.signal_names.end());
  // the firmware reported walls as it explored; the HUD counts the contest's time
  ASSERT_GT(r.beliefs.size(), 20u);
  EXPECT_GT(r.beliefs.back().value.walls.size(), r.beliefs.front().value.walls.size());
  ASSERT_GT(r.hud.size(), 100u);
  // the contest's clock, which starts when the mouse first moves (0.38 s in)
  const std::string line = r.hud[Recording::Latest(r.hud, 30.05)].value[0];
  double clock_s = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "time %lf s of 600 s", &clock_s), 1) << line;
  EXPECT_NEAR(clock_s, 30.05 - 0.38, 0.1) << line;
}

// the first of two traces' common times at which their robots are more than 1 cm apart
double FirstApart(const std::vector<TraceRow>& a, const std::vector<TraceRow>& b) {
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    EXPECT_NEAR(a[i].t_s, b[i].t_s, 1e-9);
    if (std::hypot(a[i].x_m - b[i].x_m, a[i].y_m - b[i].y_m) > 0.01) return a[i].t_s;
  }
  return -1;
}

// reading skips topics unparsed: every topic a run records is read, or is one of the two a
// replay draws from others, so a topic the recording gains is never skipped unnoticed
TEST_F(ReplayCommandTest, EveryTopicARunRecordsIsReadOrSkippedOnPurpose) {
  struct Topics : McapVisitor {
    std::set<std::string> all;
    void OnChannel(const McapChannel& channel) override { all.insert(channel.topic); }
  } topics;
  ReadMcap(Main() + "/run.mcap", topics);
  const std::set<std::string> skipped = {"/beams", "/beliefs/scene"};
  for (const std::string& s : skipped) EXPECT_EQ(topics.all.count(s), 1u) << s;
  EXPECT_EQ(topics.all.count("/robot/pose"), 1u);
  for (const std::string& topic : topics.all) {
    EXPECT_NE(ReplayReadsTopic(topic), skipped.count(topic) == 1) << topic;
  }
}

TEST_F(ReplayCommandTest, TwoRunsArePlayedTogetherSayingWhereTheyFirstPartAsTheirTracesDo) {
  // another seed: other sensor noise, a path that parts somewhere
  const testing::RunResult other = testing::UnimouseRun(
      "--scenario micromouse --link inproc:" + kFirmware + " --duration 60 --seed 7",
      "replay_seed7");
  ASSERT_EQ(other.outcome.exit_code, 1) << other.outcome.output;
  const double apart_s = FirstApart(ReadTrace(Main() + "/trace.csv"),
                                    ReadTrace(OutDir("replay_seed7") + "/trace.csv"));
  ASSERT_GT(apart_s, 0) << "the two seeds never parted";
  char expected[64];
  std::snprintf(expected, sizeof(expected), "the runs first diverge at %.3f s: ", apart_s);
  const std::string page = OutDir("replay_seed7") + "/both.html";
  const testing::Outcome o =
      testing::Unimouse("replay " + Main() + " " + OutDir("replay_seed7") + " --html " + page);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find(expected), std::string::npos) << o.output;
  // the page has both, the second as a ghost
  const std::string html = ReadTextFile(page);
  EXPECT_NE(html.find("\"ghost\":true"), std::string::npos);

  // the same run twice never parts
  const testing::Outcome same =
      testing::Unimouse("replay " + Main() + " " + Main() + "/run.mcap --html " + page);
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(
      same.output.find("the runs never diverge by more than 1 cm over the 60.000 s both cover"),
      std::string::npos)
      << same.output;
}

TEST_F(ReplayCommandTest, ARunsOwnTraceImportedAsALoggedRunNeverPartsFromIt) {
  // trace.csv starts with the columns of a pose log: time_s,x_m,y_m,yaw_rad
  const testing::Outcome o = testing::Unimouse("replay " + Main() + " --import " + Main() +
                                               "/trace.csv --html " + Main() + "/with_log.html");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("the simulation and the logged run never diverge by more than 1 cm"),
            std::string::npos)
      << o.output;

  // the same log 2 cm to the east from 10 s on parts there
  const std::vector<TraceRow> trace = ReadTrace(Main() + "/trace.csv");
  const std::string shifted = Main() + "/shifted.csv";
  {
    std::ofstream out(shifted);
    out << "# the trace, 2 cm east from 10 s on\ntime_s,x_m,y_m,yaw_rad\n";
    out.precision(17);
    for (const TraceRow& row : trace) {
      out << row.t_s << "," << row.x_m + (row.t_s >= 10 - 1e-9 ? 0.02 : 0) << "," << row.y_m << ","
          << row.yaw_rad << "\n";
    }
  }
  const testing::Outcome parted = testing::Unimouse("replay " + Main() + " --import " + shifted +
                                                    " --html " + Main() + "/x.html");
  ASSERT_EQ(parted.exit_code, 0) << parted.output;
  EXPECT_NE(parted.output.find(
                "the simulation and the logged run first diverge at 10.000 s: 2.0 cm apart"),
            std::string::npos)
      << parted.output;
}

TEST(ReplayImportTest, TheSysidSketchsEncoderLogFollowsTheRobotUntilItsWheelsSlip) {
  // the sysid sketch drives straight ramps for its first seconds, logging its encoders' totals
  // (docs/calibrate.md); integrated with the robot file's wheels, they give the path the robot
  // drove while its tyres held
  const testing::RunResult run =
      testing::UnimouseRun("--scenario sysid --link native:sysid", "replay_sysid");
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const std::string out = OutDir("replay_sysid");
  const Recording r = ReadRecording(out);
  const RobotSpec robot = ParseRobotSpec(r.attachments.at(r.robots[0].file), r.robots[0].file);
  const RecordedRobot logged =
      ReadImportedRun(out + "/sysid.csv", &robot, r.robots[0].poses[0].value);
  const std::optional<Divergence> apart = FirstDivergence(r.robots[0], logged);
  ASSERT_TRUE(apart.has_value());
  // over 3 m of ramps within 1 cm (0.3 %)
  EXPECT_GT(apart->t_s, 8.0);
  EXPECT_GT(std::hypot(apart->a.x_m - r.robots[0].poses[0].value.x_m,
                       apart->a.y_m - r.robots[0].poses[0].value.y_m),
            3.0);
}

TEST(ReplayImportTest, ABadLogIsOneLineWithItsLineNumber) {
  const std::string dir = testing::FreshDirectory("bad_logs");
  const std::map<std::string, std::pair<std::string, std::string>> logs = {
      {"no_yaw.csv", {"time_s,x_m,y_m\n0,0,0\n1,0,0\n", ":1: no column yaw_rad"}},
      {"nan.csv",
       {"time_s,x_m,y_m,yaw_rad\n0,0,0,0\n0.5,nan,0,0\n", ":3: x_m 'nan' is not a finite number"}},
      {"back.csv",
       {"time_s,x_m,y_m,yaw_rad\n0,0,0,0\n2,0,0,0\n1,0,0,0\n", ":4: time_s goes backwards"}},
      {"short.csv",
       {"time_s,x_m,y_m,yaw_rad\n0,0,0,0\n",
        ": a logged run needs a header and at least two rows"}},
      {"counts.csv",
       {"time_s,left_counts,right_counts\n0,0,0\n1,5,5\n",
        ":1: an encoder log needs the robot's file"}},
  };
  for (const auto& [name, log] : logs) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << log.first;
    try {
      ReadImportedRun(path, nullptr, {});
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + log.second, 0), 0u) << e.what();
    }
  }
}

TEST_F(ReplayCommandTest, ABadLogOrRecordingIsExitCode2WithOneSentenceAndNothingWritten) {
  const std::string dir = testing::FreshDirectory("bad_replays");
  std::ofstream(dir + "/empty.mcap") << "";
  std::ofstream(dir + "/notes.txt") << "time_s,x_m\n";
  std::ofstream(dir + "/nan.csv") << "time_s,x_m,y_m,yaw_rad\n0,0,0,0\n1,nan,0,0\n";
  {
    // a recording of a later format, and an MCAP file unimouse did not record
    McapWriter later(dir + "/later.mcap", {});
    later.AddMetadata("unimouse.recording", {{"format", "99"}});
    later.Close();
    McapWriter foreign(dir + "/foreign.mcap", {});
    foreign.Close();
  }
  const std::map<std::string, std::string> cases = {
      {dir + "/empty.mcap", dir + "/empty.mcap: the file is empty, not an MCAP recording"},
      {dir + "/notes.txt",
       dir + "/notes.txt: not an MCAP recording (it does not start with MCAP's magic)"},
      {dir + "/later.mcap", dir + "/later.mcap: a recording of format 99, made by a newer unimouse "
                                  "than this one (it reads format 1)"},
      {dir + "/foreign.mcap", dir + "/foreign.mcap: an MCAP file that unimouse did not record (no "
                                    "unimouse.recording metadata; written by unimouse)"},
      {dir + "/missing", dir + "/missing: no such file or folder"},
      {dir, dir + ": no run.mcap in this folder (was the run made with --record off?)"},
      {Main() + " --import " + dir + "/nan.csv",
       dir + "/nan.csv:3: x_m 'nan' is not a finite number"},
      {Main() + " --signal no.such", "--signal no.such: the recording has no such signal"},
  };
  for (const auto& [arguments, sentence] : cases) {
    const testing::Outcome o =
        testing::Unimouse("replay " + arguments + " --html " + dir + "/page.html");
    EXPECT_EQ(o.exit_code, 2) << arguments << ": " << o.output;
    EXPECT_NE(o.output.find(sentence + "\n"), std::string::npos) << arguments << ": " << o.output;
    EXPECT_FALSE(fs::exists(dir + "/page.html")) << arguments;
  }
}

TEST_F(ReplayCommandTest, ARecordingCutShortPlaysUpToItsLastWholeChunkWithAWarning) {
  const std::string bytes = ReadTextFile(Main() + "/run.mcap");
  const std::string cut = testing::FreshDirectory("cut_recording") + "/run.mcap";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const testing::Outcome o = testing::Unimouse("replay " + cut + " --html " + cut + ".html");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("  warning: the recording was cut short (the file ends at byte "),
            std::string::npos)
      << o.output;
  const Recording r = ReadRecording(cut);
  // about half the minute, each pose where the whole recording has it
  EXPECT_GT(r.end_s, 10);
  EXPECT_LT(r.end_s, 50);
  const Recording whole = ReadRecording(Main());
  for (size_t i = 0; i < r.robots[0].poses.size(); ++i) {
    ASSERT_EQ(r.robots[0].poses[i].value.x_m, whole.robots[0].poses[i].value.x_m) << i;
  }
  EXPECT_TRUE(fs::exists(cut + ".html"));
}

// where the window's screenshot shows the robot: the centre of its plate's green (pixels whose
// neighbours two pixels away are green too, so that a 1-pixel ToF beam does not count), mapped
// to metres through the maze's outermost red posts, whose outer edges are at -6 mm and 16 cells
// + 6 mm
std::optional<std::pair<double, double>> RobotInScreenshot(const std::string& png) {
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(png, &width, &height);
  auto at = [&](int x, int y) { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; };
  auto green = [&](int x, int y) {
    const uint8_t* p = at(x, y);
    return p[1] > p[0] + 40 && p[1] > p[2] + 40;
  };
  int min_x = width, max_x = -1, min_y = height, max_y = -1;
  double sum_x = 0, sum_y = 0, n = 0;
  for (int y = 2; y < height - 30; ++y) {  // above the timeline
    for (int x = 2; x < width - 2; ++x) {
      const uint8_t* p = at(x, y);
      if (p[0] > 150 && p[1] < 90 && p[2] < 90) {
        min_x = std::min(min_x, x), max_x = std::max(max_x, x);
        min_y = std::min(min_y, y), max_y = std::max(max_y, y);
      }
      if (green(x, y) && green(x - 2, y) && green(x + 2, y) && green(x, y - 2) && green(x, y + 2)) {
        sum_x += x + 0.5;
        sum_y += y + 0.5;
        ++n;
      }
    }
  }
  if (n < 100 || max_x < 0) return std::nullopt;
  const double span_m = 16 * 0.18 + 0.012;
  const double x_m = -0.006 + (sum_x / n - min_x) / (max_x + 1 - min_x) * span_m;
  const double y_m = -0.006 + (max_y + 1 - sum_y / n) / (max_y + 1 - min_y) * span_m;
  return std::make_pair(x_m, y_m);
}

TEST_F(ReplayCommandTest, TheWindowShowsTheRobotWhereTheRecordingPutsItAndTheHudOfThatTime) {
  if (!testing::HaveXvfbRun()) GTEST_SKIP() << "xvfb-run is not installed (apt install xvfb xauth)";
  const std::vector<TraceRow> trace = ReadTrace(Main() + "/trace.csv");
  const std::map<int64_t, double> left_voltage_v =
      ReadTraceColumn(Main() + "/trace.csv", "left.voltage_v");
  const Recording r = ReadRecording(Main());
  for (const double t : {12.34, 47.5}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const std::string dir = testing::FreshDirectory("replay_window");
    char at[32];
    std::snprintf(at, sizeof(at), "%g", t);
    const testing::Outcome o =
        testing::Unimouse("replay " + Main() + " --at " + at +
                              " --paused --view-frames 2 --signal left.voltage_v --out " + dir,
                          testing::OnVirtualDisplay());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    char said[96];
    std::snprintf(said, sizeof(said), "  screenshot: %s/replay.png at %.3f s\n", dir.c_str(), t);
    EXPECT_NE(o.output.find(said), std::string::npos) << o.output;
    // the HUD of that time: the scenario's lines as the recording has them then
    for (const std::string& line : r.hud[Recording::Latest(r.hud, t)].value) {
      EXPECT_NE(o.output.find("    " + line + "\n"), std::string::npos) << line << "\n" << o.output;
    }
    // and the firmware's values then: the micromouse example reports where it believes it is
    // at each cell it reaches, less than a cell from where the robot is
    const size_t firmware = o.output.find("    firmware: est_theta_rad=");
    ASSERT_NE(firmware, std::string::npos) << o.output;
    double theta = 0, est_x = 0, est_y = 0;
    ASSERT_EQ(std::sscanf(o.output.c_str() + firmware,
                          "    firmware: est_theta_rad=%lf est_x_m=%lf est_y_m=%lf", &theta, &est_x,
                          &est_y),
              3)
        << o.output;
    const TraceRow& now = trace[static_cast<size_t>(std::llround(t / 0.01))];
    EXPECT_LT(std::hypot(est_x - now.x_m, est_y - now.y_m), 0.18) << o.output;

    // a chosen signal at the cursor: the left motor's voltage in the trace's row then
    const size_t voltage = o.output.find("    left.voltage_v = ");
    ASSERT_NE(voltage, std::string::npos) << o.output;
    EXPECT_NEAR(std::stod(o.output.substr(voltage + 21)), left_voltage_v.at(std::llround(t * 1000)),
                1e-4);

    const auto shown = RobotInScreenshot(dir + "/replay.png");
    ASSERT_TRUE(shown.has_value());
    // the trace's row at t (every 10 ms): the perspective of wall tops and plate differ by a
    // centimetre at the maze's edge
    const TraceRow& row = trace[static_cast<size_t>(std::llround(t / 0.01))];
    ASSERT_NEAR(row.t_s, t, 1e-6);
    EXPECT_NEAR(shown->first, row.x_m, 0.02);
    EXPECT_NEAR(shown->second, row.y_m, 0.02);
  }
}

}  // namespace
}  // namespace unimouse

namespace unimouse {
namespace {

// the fuzz target's seed (tests/data/short_run.mcap, 0.3 s of the contest) reads the same from
// its bytes as from its file, and every prefix of it is a recording cut short, a whole one (cut
// in its summary) or one sentence, never a crash
// Poses and signals, most of a recording, are read by a quick reader of their own (recording.cc,
// QuickJson) that leaves what it does not expect to the JSON parser: whatever the text, each
// message reads as that parser's document of it says, or is skipped when the document has no
// pose or no signals in it.
TEST(ReplayRecordingTest, PosesAndSignalsReadAsAJsonParserReadsThem) {
  const std::vector<std::string> numbers = {"0",
                                            "-0",
                                            "1",
                                            "-1.5",
                                            "0.1",
                                            "1e-3",
                                            "-2.5E+2",
                                            "123456789012345678",
                                            "-9223372036854775808",
                                            "18446744073709551615",
                                            "18446744073709551616",
                                            "-9223372036854775809",
                                            "1e308",
                                            "1e999",
                                            "5e-324",
                                            "0.30000000000000004",
                                            "01",
                                            "1.",
                                            ".5",
                                            "-",
                                            "+1",
                                            "1e",
                                            "true",
                                            "null",
                                            "\"1\"",
                                            "[1]",
                                            "{\"a\":1}",
                                            "1 2"};
  std::vector<std::string> poses, signals;
  for (const std::string& n : numbers) {
    poses.push_back(R"({"timestamp":{"sec":0,"nsec":0},"parent_frame_id":"world",)"
                    R"("translation":{"x":)" +
                    n +
                    R"(,"y":0.25,"z":0},)"
                    R"("rotation":{"x":0,"y":0,"z":)" +
                    n + R"(,"w":1}})");
    signals.push_back(R"({"timestamp":{"sec":0,"nsec":0},"values":{"b.x":)" + n +
                      R"(,"a.y":2,"c":null}})");
  }
  // spaces, escapes, text beyond ASCII, keys in another order, a value twice, damage
  poses.push_back(
      " { \"rotation\" : {\"w\" : 0.5 , \"z\":-0.5} ,\n\t\"translation\":{\"y\":1,"
      "\"x\":2} } ");
  poses.push_back(
      R"({"translation":{"x":1,"y":2},"rotation":{"z":0,"w":1},"note":"caf\u00e9 \"x\""})");
  poses.push_back(
      "{\"translation\":{\"x\":1,\"y\":2},\"rotation\":{\"z\":0,\"w\":1},\"t\":\"\xc3\xa9\"}");
  poses.push_back(R"({"translation":{"x":1,"y":2,"x":3},"rotation":{"z":0,"w":1}})");
  poses.push_back(R"({"translation":{"x":1},"rotation":{"z":0,"w":1}})");
  poses.push_back(R"({"translation":[1,2],"rotation":{"z":0,"w":1}})");
  poses.push_back(R"({"translation":{"x":1,"y":2},"rotation":{"z":0,"w":1})");
  poses.push_back(R"({"translation":{"x":1,"y":2},"rotation":{"z":0,"w":1}}})");
  poses.push_back(R"([{"translation":{"x":1,"y":2},"rotation":{"z":0,"w":1}}])");
  poses.push_back(R"({"translation":{"x":{"x":5},"y":2},"rotation":{"z":0,"w":1}})");
  poses.push_back(R"({"a":[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]],"translation":{"x":1,"y":2},)"
                  R"("rotation":{"z":0,"w":1}})");
  poses.push_back("");
  signals.push_back(R"({"values":{"a.y":1,"b\u002ex":2,"a.y":3}})");
  signals.push_back(R"({"values":[1,2]})");
  signals.push_back(R"({"values":{"a.y":{"v":1},"b.x":[1],"c":"text"}})");
  signals.push_back(R"({"values":{"z.new":1,"c":true}})");
  signals.push_back(R"({"values":{"a.y":1,"b.x":2,"c":3)");

  const std::string path = testing::FreshDirectory("quick_json") + "/run.mcap";
  {
    McapWriter writer(path, {});
    writer.AddMetadata("unimouse.recording", {{"format", "1"}});
    const uint16_t pose = writer.AddChannel(0, "/robot/pose", "json");
    const uint16_t values = writer.AddChannel(0, "/signals", "json");
    for (size_t i = 0; i < poses.size(); ++i) writer.Write(pose, i * 1'000'000, poses[i]);
    for (size_t i = 0; i < signals.size(); ++i) writer.Write(values, i * 1'000'000, signals[i]);
    writer.Close();
  }
  const Recording read = ReadRecording(path);

  // the parser's documents: a pose needs its four numbers' places, the signals their object;
  // anything else in a number's place is NaN
  auto number = [](const json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  auto same = [](double a, double b) {  // to the bit, NaN as NaN
    return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0;
  };
  std::vector<Pose2D> expected_poses;
  for (const std::string& text : poses) {
    const json m = json::parse(text, nullptr, false);
    try {
      if (m.is_discarded() || !m.is_object()) continue;
      const json& q = m.at("rotation");
      const double yaw = 2 * std::atan2(number(q.at("z")), number(q.at("w")));
      expected_poses.push_back({number(m.at("translation").at("x")),
                                number(m.at("translation").at("y")),
                                std::remainder(yaw, 2 * std::numbers::pi)});
    } catch (const json::exception&) {
    }
  }
  ASSERT_EQ(read.robots.size(), 1u);
  ASSERT_EQ(read.robots[0].poses.size(), expected_poses.size());
  for (size_t i = 0; i < expected_poses.size(); ++i) {
    const Pose2D& got = read.robots[0].poses[i].value;
    EXPECT_TRUE(same(got.x_m, expected_poses[i].x_m)) << i << ": " << got.x_m;
    EXPECT_TRUE(same(got.y_m, expected_poses[i].y_m)) << i << ": " << got.y_m;
    EXPECT_TRUE(same(got.yaw_rad, expected_poses[i].yaw_rad)) << i << ": " << got.yaw_rad;
  }
  EXPECT_GE(expected_poses.size(), 20u);

  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  for (const std::string& text : signals) {
    const json m = json::parse(text, nullptr, false);
    if (m.is_discarded() || !m.is_object() || !m.contains("values") || !m["values"].is_object()) {
      continue;
    }
    const json& values = m["values"];
    if (names.empty()) {
      for (const auto& [name, value] : values.items()) names.push_back(name);
    }
    std::vector<double> row;
    for (const std::string& name : names) {
      row.push_back(values.contains(name) ? number(values[name])
                                          : std::numeric_limits<double>::quiet_NaN());
    }
    rows.push_back(row);
  }
  EXPECT_EQ(read.signal_names, names);
  ASSERT_EQ(read.signal_rows.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    for (size_t k = 0; k < names.size(); ++k) {
      EXPECT_TRUE(same(read.signal_rows[i][k], rows[i][k]))
          << i << " " << names[k] << ": " << read.signal_rows[i][k] << " vs " << rows[i][k];
    }
  }
}

TEST(ReplayRecordingTest, ARecordingReadsTheSameFromItsBytesAndAnyPrefixIsReadOrRefused) {
  const std::string path = UNIMOUSE_SOURCE_DIR "/tests/data/short_run.mcap";
  const Recording file = ReadRecording(path);
  const std::string bytes = ReadTextFile(path);
  const Recording parsed = ParseRecording(bytes, path);
  ASSERT_EQ(parsed.robots.size(), 1u);
  ASSERT_EQ(parsed.robots[0].poses.size(), file.robots[0].poses.size());
  EXPECT_EQ(parsed.robots[0].poses.size(), 31u);  // 0.3 s at 100 Hz, and time 0
  EXPECT_EQ(parsed.attachments, file.attachments);
  size_t read = 0;
  for (size_t n = 0; n < bytes.size(); n += 97) {
    try {
      // said to be cut short, or everything there (the file ends in its summary, after its
      // data): never less than the whole without saying so
      const Recording cut = ParseRecording(std::string_view(bytes).substr(0, n), path);
      if (cut.cut_short.empty()) {
        EXPECT_EQ(cut.robots[0].poses.size(), 31u) << n;
        EXPECT_EQ(cut.attachments, file.attachments) << n;
      }
      ++read;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(read, 0u);
}

}  // namespace
}  // namespace unimouse
