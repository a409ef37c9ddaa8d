// SPDX-License-Identifier: GPL-3.0-or-later
// The replay page as a student sees it: loaded from a file into headless Chromium (Debian's
// `chromium`), its scripts run, the rendered DOM read back with --dump-dom and the drawing with
// --screenshot. The robot's place on the screenshot is checked against the circle the test
// itself drove it along, and, on the page `unimouse replay --html` writes after the main job,
// against the run's trace.csv; that page's HUD against the recording as the tests' own MCAP
// reader reads it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "headless_chromium.h"
#include "mcap_json.h"
#include "replay_page.h"
#include "replay_page_assets.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kCell_m = 0.18;
constexpr double kEnd_s = 10.0;
// robot 0 drives a circle of radius 0.2 m around (0.36, 0.36) at 0.5 m/s, counter-clockwise
constexpr double kCentre_m = 0.36;
constexpr double kRadius_m = 0.2;
constexpr double kRate_rad_per_s = 0.5 / kRadius_m;
constexpr double kLength_m = 0.1;
constexpr double kWidth_m = 0.08;

struct Pose {
  double x, y, yaw;
};

// where robot 0 is at time t (its yaw in (-pi, pi], as a recording has it); the ghost is `lag`
// radians behind it on the same circle
Pose CirclePose(double t, double lag = 0) {
  const double angle = kRate_rad_per_s * t - lag;
  const double yaw = angle + std::numbers::pi / 2;
  return {kCentre_m + kRadius_m * std::cos(angle), kCentre_m + kRadius_m * std::sin(angle),
          std::atan2(std::sin(yaw), std::cos(yaw))};
}

json Robot(const std::string& name, bool ghost, double lag) {
  json robot = {{"name", name},          {"ghost", ghost},      {"source", "firmware"},
                {"length_m", kLength_m}, {"width_m", kWidth_m}, {"t", json::array()},
                {"x", json::array()},    {"y", json::array()},  {"yaw", json::array()}};
  for (int k = 0; k <= 1000; ++k) {  // 100 Hz for 10 s
    const double t = k * 0.01;
    const Pose pose = CirclePose(t, lag);
    robot["t"].push_back(t);
    robot["x"].push_back(pose.x);
    robot["y"].push_back(pose.y);
    robot["yaw"].push_back(pose.yaw);
  }
  return robot;
}

json Box(const char* kind, double x, double y, double size_x, double size_y, double yaw) {
  return {{"kind", kind}, {"x", x}, {"y", y}, {"size_x", size_x}, {"size_y", size_y}, {"yaw", yaw}};
}

// a 4 x 4 maze's posts and outer walls and one inner wall; robot 0 and a ghost on the circle;
// log line k at k / 2 s saying "line k", and HUD, values, beliefs and events at known times
json TestData() {
  json data = {{"title", "circle run"}, {"end_s", kEnd_s}, {"cell_m", kCell_m}};
  data["scenery"] = json::array();
  constexpr double kThick_m = 0.012;
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      data["scenery"].push_back(Box("post", i * kCell_m, j * kCell_m, kThick_m, kThick_m, 0));
    }
  }
  for (int i = 0; i < 4; ++i) {
    const double along = (i + 0.5) * kCell_m, length = kCell_m - kThick_m;
    data["scenery"].push_back(Box("wall", along, 0, length, kThick_m, 0));
    data["scenery"].push_back(Box("wall", along, 4 * kCell_m, length, kThick_m, 0));
    data["scenery"].push_back(Box("wall", 0, along, length, kThick_m, std::numbers::pi / 2));
    data["scenery"].push_back(
        Box("wall", 4 * kCell_m, along, length, kThick_m, std::numbers::pi / 2));
  }
  data["scenery"].push_back(
      Box("wall", kCell_m, 0.5 * kCell_m, kCell_m - kThick_m, kThick_m, std::numbers::pi / 2));
  data["robots"] = {Robot("mouse", false, 0), Robot("ghost", true, 0.8)};

  json t = json::array(), speed = json::array(), wave = json::array();
  for (int k = 0; k <= 100; ++k) {
    t.push_back(k * 0.1);
    speed.push_back(k % 20 == 10 ? json(nullptr) : json(0.5));
    wave.push_back(std::sin(k * 0.1));
  }
  data["signals"] = {
      {"t", t},
      {"series",
       {{{"name", "speed_mps"}, {"values", speed}}, {{"name", "wave"}, {"values", wave}}}}};

  data["log"] = json::array();
  for (int k = 0; k < 20; ++k) {
    data["log"].push_back({{"t", k * 0.5},
                           {"level", 1 + k % 4},
                           {"name", "fw"},
                           {"message", "line " + std::to_string(k)}});
  }
  data["log"].push_back({{"t", 3.2},
                         {"level", 4},
                         {"name", "fw"},
                         {"message", "</script><script>document.title='owned'</script>"}});
  data["events"] = {{{"t", 1.0}, {"kind", "cell"}, {"robot", "mouse"}, {"text", "entered (1, 0)"}},
                    {{"t", 6.0}, {"kind", "goal"}, {"robot", "mouse"}, {"text", "reached"}}};
  data["hud"] = {{{"t", 2.0}, {"lines", {"hud from two", "second line"}}},
                 {{"t", 5.0}, {"lines", {"hud from five"}}}};
  data["values"] = {{{"t", 2.0}, {"values", {{"speed_target", 0.25}, {"cells_known", 3}}}},
                    {{"t", 7.0}, {"values", {{"speed_target", 0.75}, {"cells_known", 9}}}}};
  data["beliefs"] = {{{"t", 2.0},
                      {"walls", {{0, 0, 9, 15}, {1, 1, 2, 2}}},
                      {"visited", {{0, 0}, {1, 0}}},
                      {"path", {{0, 0}, {1, 0}, {1, 1}}},
                      {"colours", {{2, 2, "#ffeb3b"}}},
                      {"texts", {{3, 3, "12"}}}}};
  data["divergence"] = {{"t", 4.0}, {"distance_m", 0.05}, {"text", "the ghost went another way"}};
  return data;
}

size_t Count(const std::string& text, const std::string& part) {
  size_t count = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

class ReplayPageBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string program = testing::FindProgram("chromium");
    if (program.empty()) GTEST_SKIP() << "no chromium on PATH (Debian: apt-get install chromium)";
    dir_ = testing::FreshDirectory("replay");
    chromium_.emplace(program, dir_ / "chromium-profile");
    WriteReplayPage(TestData(), (dir_ / "replay.html").string());
  }

  std::string PageAddress(const std::string& fragment) {
    return "file://" + (dir_ / "replay.html").string() + "#" + fragment;
  }

  // the page's DOM after its scripts ran, opened at `fragment`
  std::string RenderedDom(const std::string& fragment) {
    return chromium_->Dom(PageAddress(fragment));
  }

  std::optional<testing::HeadlessChromium> chromium_;
  fs::path dir_;
};

TEST_F(ReplayPageBrowserTest, DrawsRobot0WhereItsCircleHasItAtTheCursor) {
  // 3.1425 s is a quarter of the way between two samples whose yaws are either side of pi: the
  // long way round would turn the robot a quarter turn
  for (const double t : {2.345, 3.1425, 7.5}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const testing::ShownRobot shown = testing::RobotOnScreen(
        *chromium_, PageAddress("t=" + std::to_string(t)), dir_ / "screenshot.png");
    const Pose expected = CirclePose(t);

    // all of its body but its edges and its heading mark, and nothing else in its colour
    const double area_px = kLength_m * kWidth_m * shown.pixels_per_m * shown.pixels_per_m;
    EXPECT_GT(shown.blob.count, 0.8 * area_px);
    EXPECT_LT(shown.blob.count, 1.02 * area_px);
    EXPECT_NEAR(shown.x_m, expected.x, 0.01);
    EXPECT_NEAR(shown.y_m, expected.y, 0.01);
    // its length lies along its heading (a rectangle's axis is known modulo a half turn)
    EXPECT_NEAR(std::remainder(shown.yaw_rad - expected.yaw, std::numbers::pi), 0, 0.07);
  }
}

TEST_F(ReplayPageBrowserTest, ShowsTheCursorsHudValuesAndLogLines) {
  const std::string dom = RenderedDom("t=5.5");
  EXPECT_NE(dom.find("data-cursor=\"5.5\""), std::string::npos);
  EXPECT_NE(dom.find("<span id=\"time\">5.500 s</span>"), std::string::npos);

  // the HUD and the values of the entries current at 5.5 s, not the ones before or after
  EXPECT_NE(dom.find("<div class=\"hud-line\">hud from five</div>"), std::string::npos);
  EXPECT_EQ(dom.find("<div class=\"hud-line\">hud from two</div>"), std::string::npos);
  EXPECT_NE(dom.find("<th>speed_target</th><td class=\"num\">0.25</td>"), std::string::npos);
  EXPECT_NE(dom.find("<th>cells_known</th><td class=\"num\">3</td>"), std::string::npos);
  EXPECT_EQ(dom.find("0.75</td>"), std::string::npos);

  // the last 12 log lines up to the cursor: line 11 at 5.5 s back to line 1 at 0.5 s, with the
  // injected message among them as text; nothing later
  EXPECT_EQ(Count(dom, "<tr class=\"log-line"), 12u);
  EXPECT_NE(dom.find("<td class=\"num\">5.500</td><td class=\"level\">error</td><td "
                     "class=\"name\">fw</td><td class=\"message\">line 11</td>"),
            std::string::npos);
  EXPECT_NE(dom.find("<td class=\"message\">line 1</td>"), std::string::npos);
  EXPECT_EQ(dom.find("<td class=\"message\">line 0</td>"), std::string::npos);
  EXPECT_EQ(dom.find("<td class=\"message\">line 12</td>"), std::string::npos);
  EXPECT_NE(dom.find("<td class=\"message\">&lt;/script&gt;&lt;script&gt;document.title='owned'"
                     "&lt;/script&gt;</td>"),
            std::string::npos);

  // one plot per series, named, with its range
  EXPECT_EQ(Count(dom, "<figure class=\"plot\">"), 2u);
  EXPECT_NE(dom.find("<figcaption>speed_mps</figcaption>"), std::string::npos);
  EXPECT_NE(dom.find("<figcaption>wave</figcaption>"), std::string::npos);
  EXPECT_NE(dom.find("<span class=\"plot-max\">0.5</span>"), std::string::npos);

  // the events, the one current marked, and the divergence
  EXPECT_NE(dom.find("<li class=\"current\"><button class=\"event\" type=\"button\"><span "
                     "class=\"time\">1.000</span><span class=\"kind\">cell</span>"),
            std::string::npos);
  EXPECT_NE(dom.find("Divergence at 4.000 s, 0.05 m apart: the ghost went another way"),
            std::string::npos);
  EXPECT_EQ(Count(dom, "class=\"divergence-mark\""), 1u);

  // the text from the data stayed text: the page's own two scripts are all it has
  EXPECT_NE(dom.find("<title>Replay: circle run</title>"), std::string::npos);
  EXPECT_EQ(dom.find("owned</title>"), std::string::npos);
  EXPECT_EQ(Count(dom, "<script"), 2u);
}

TEST_F(ReplayPageBrowserTest, ShowsTheLaterEntriesAtALaterCursor) {
  const std::string dom = RenderedDom("t=7.5&speed=4");
  EXPECT_NE(dom.find("data-cursor=\"7.5\""), std::string::npos);
  EXPECT_NE(dom.find("<option value=\"4\" selected"), std::string::npos) << "the speed select";
  EXPECT_NE(dom.find("<th>speed_target</th><td class=\"num\">0.75</td>"), std::string::npos);
  EXPECT_NE(dom.find("<td class=\"message\">line 15</td>"), std::string::npos);
  EXPECT_EQ(dom.find("<td class=\"message\">line 16</td>"), std::string::npos);
}

// the requests a page made (Chromium's own, for updates and accounts, have no initiator) whose
// address is not a file
std::vector<std::string> NetworkRequestsOfPages(const std::string& net_log_path) {
  std::vector<std::string> urls;
  const json log = json::parse(ReadTextFile(net_log_path));
  const int start_job = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"].get<int>();
  for (const auto& event : log["events"]) {
    // the job's start names its address and who asked (its end only how it ended)
    if (event.value("type", -1) != start_job || !event.contains("params")) continue;
    const json& params = event["params"];
    if (!params.contains("url")) continue;
    if (params.value("initiator", "") == "not an origin") continue;
    const std::string url = params.value("url", "");
    if (url.rfind("file:", 0) != 0) urls.push_back(url);
  }
  return urls;
}

TEST_F(ReplayPageBrowserTest, FetchesNothingFromTheNetwork) {
  const std::string net_log = (dir_ / "net-log.json").string();
  chromium_->Run("--log-net-log=" + net_log + " --dump-dom", PageAddress("t=2&speed=2"));
  EXPECT_EQ(NetworkRequestsOfPages(net_log), std::vector<std::string>{});

  // the check sees a page's request: a page with an image from a server is caught
  std::ofstream(dir_ / "fetching.html") << "<!DOCTYPE html><img src=\"http://127.0.0.1:9/x.png\">";
  const std::string control_log = (dir_ / "control-net-log.json").string();
  chromium_->Run("--log-net-log=" + control_log + " --dump-dom",
                 "file://" + (dir_ / "fetching.html").string());
  EXPECT_EQ(NetworkRequestsOfPages(control_log),
            std::vector<std::string>{"http://127.0.0.1:9/x.png"});
}

// ---- the page of a real run: `unimouse replay OUT --html PAGE` after the main job
// ----------------

// trace.csv's pose at `t`, linear between the two rows around it (the trace is written by the run
// itself, beside the recording the page is made from)
Pose TracePoseAt(const std::string& trace_csv, double t) {
  std::ifstream in(trace_csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::istringstream names(line);
  for (std::string name; std::getline(names, name, ',');) header.push_back(name);
  auto column = [&header](const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const size_t time = column("time_s"), x = column("x_m"), y = column("y_m"),
               yaw = column("yaw_rad");
  EXPECT_LT(std::max({time, x, y, yaw}), header.size()) << trace_csv << ": " << line;
  std::vector<double> before;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    if (row.size() != header.size()) continue;
    if (row[time] >= t && !before.empty()) {
      const double f = (t - before[time]) / (row[time] - before[time]);
      // the yaw the short way round: the trace's is in (-pi, pi]
      return {before[x] + f * (row[x] - before[x]), before[y] + f * (row[y] - before[y]),
              before[yaw] + f * std::remainder(row[yaw] - before[yaw], 2 * std::numbers::pi)};
    }
    before = row;
  }
  ADD_FAILURE() << trace_csv << " has no rows around " << t << " s";
  return {NAN, NAN, NAN};
}

// the lines of the recording's latest /hud message at or before `t`
std::vector<std::string> RecordedHudAt(const json& recording, double t) {
  const uint64_t at_ns = static_cast<uint64_t>(std::llround(t * 1e9));
  uint64_t latest_ns = 0;
  std::vector<std::string> lines;
  for (const json& m : testing::OnTopic(recording, "/hud")) {
    const uint64_t log_ns = m["log_time"].get<uint64_t>();
    if (log_ns <= at_ns && log_ns >= latest_ns) {
      latest_ns = log_ns;
      lines = m["data"]["lines"].get<std::vector<std::string>>();
    }
  }
  return lines;
}

// a text as Chromium writes it into a DOM's text node
std::string AsDomText(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') {
      out += "&amp;";
    } else if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else {
      out += c;
    }
  }
  return out;
}

// what the elements of `dom` that open with `open` hold, up to `close`, in the DOM's order
std::vector<std::string> Contents(const std::string& dom, const std::string& open,
                                  const std::string& close) {
  std::vector<std::string> contents;
  for (size_t at = dom.find(open); at != std::string::npos; at = dom.find(open, at + 1)) {
    const size_t start = at + open.size();
    contents.push_back(dom.substr(start, dom.find(close, start) - start));
  }
  return contents;
}

// the captions of the page's plots, in name order
std::vector<std::string> PlotNames(const std::string& dom) {
  std::vector<std::string> names;
  const std::string figure = "<figure class=\"plot\">";
  for (size_t at = dom.find(figure); at != std::string::npos; at = dom.find(figure, at + 1)) {
    const std::string caption = "<figcaption>";
    const size_t start = dom.find(caption, at) + caption.size();
    names.push_back(dom.substr(start, dom.find("</figcaption>", start) - start));
  }
  std::sort(names.begin(), names.end());
  return names;
}

const std::string kMainJob =
    "--scenario micromouse --link inproc:" UNIMOUSE_FIRMWARE_DIR "/micromouse.so";

class ReplayPageOfARunBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string program = testing::FindProgram("chromium");
    if (program.empty()) GTEST_SKIP() << "no chromium on PATH (Debian: apt-get install chromium)";
    dir_ = testing::FreshDirectory("replay-run");
    chromium_.emplace(program, dir_ / "chromium-profile");
  }

  std::optional<testing::HeadlessChromium> chromium_;
  fs::path dir_;
};

TEST_F(ReplayPageOfARunBrowserTest, ShowsTheMainJobAsItsTraceAndRecordingHaveIt) {
  const testing::RunResult run =
      testing::UnimouseRun(kMainJob + " --duration 120", "replay_page_main_job");
  const std::string out = (fs::temp_directory_path() / "replay_page_main_job").string();
  // the contest is not decided in 120 s, but the run itself is whole
  EXPECT_EQ(run.result.value("status", ""), "completed") << run.outcome.output;
  ASSERT_TRUE(fs::exists(out + "/run.mcap")) << run.outcome.output;
  ASSERT_TRUE(fs::exists(out + "/trace.csv")) << run.outcome.output;
  const std::string page = (dir_ / "main_job.html").string();
  const testing::Outcome replay = testing::Unimouse("replay " + out + " --html " + page);
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  const std::string address = "file://" + page;

  // while it drives east, while it turns on the spot (its axis diagonal), while it drives west
  for (const double t : {23.456, 95.365, 97.5}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const testing::ShownRobot shown = testing::RobotOnScreen(
        *chromium_, address + "#t=" + std::to_string(t), dir_ / "screenshot.png");
    ASSERT_GT(shown.blob.count, 100) << "robot 0 is not on the screenshot";
    const Pose expected = TracePoseAt(out + "/trace.csv", t);
    EXPECT_NEAR(shown.x_m, expected.x, 0.01);
    EXPECT_NEAR(shown.y_m, expected.y, 0.01);
    EXPECT_NEAR(std::remainder(shown.yaw_rad - expected.yaw, std::numbers::pi), 0, 0.07);
  }

  const std::string dom = chromium_->Dom(address + "#t=23.456");
  // the HUD of the recording's latest /hud message at or before the cursor, read back by the
  // tests' own MCAP reader
  const json recording = testing::ReadRecording(out + "/run.mcap");
  ASSERT_TRUE(recording.is_object());
  std::vector<std::string> hud = RecordedHudAt(recording, 23.456);
  ASSERT_FALSE(hud.empty()) << "the recording has no HUD before 23.456 s";
  for (std::string& line : hud) line = AsDomText(line);
  EXPECT_EQ(Contents(dom, "<div class=\"hud-line\">", "</div>"), hud);

  // the default plots: what the motors get and the encoders and ToF sensors say, not the battery
  EXPECT_EQ(PlotNames(dom),
            (std::vector<std::string>{"left.current_a", "left.encoder_counts", "left.voltage_v",
                                      "right.current_a", "right.encoder_counts", "right.voltage_v",
                                      "tof.front_m", "tof.left_m", "tof.right_m"}));
  EXPECT_EQ(dom.find("battery.voltage_v"), std::string::npos);

  const std::string net_log = (dir_ / "net-log.json").string();
  chromium_->Run("--log-net-log=" + net_log + " --dump-dom", address + "#t=97.5&speed=4");
  EXPECT_EQ(NetworkRequestsOfPages(net_log), std::vector<std::string>{});
}

TEST_F(ReplayPageOfARunBrowserTest, PlotsOnlyTheSignalsAsked) {
  const testing::RunResult run =
      testing::UnimouseRun(kMainJob + " --duration 1", "replay_page_signal_job");
  const std::string out = (fs::temp_directory_path() / "replay_page_signal_job").string();
  ASSERT_TRUE(fs::exists(out + "/run.mcap")) << run.outcome.output;
  const std::string page = (dir_ / "signal.html").string();
  const testing::Outcome replay =
      testing::Unimouse("replay " + out + " --html " + page + " --signal left.command");
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_EQ(PlotNames(chromium_->Dom("file://" + page + "#t=0.5")),
            std::vector<std::string>{"left.command"});
}

// no browser: an unknown signal is the user's mistake, said before anything is written
TEST(ReplayPageTest, RefusesASignalTheRecordingHasNot) {
  const testing::RunResult run =
      testing::UnimouseRun(kMainJob + " --duration 1", "replay_page_bad_signal_job");
  const std::string out = (fs::temp_directory_path() / "replay_page_bad_signal_job").string();
  ASSERT_TRUE(fs::exists(out + "/run.mcap")) << run.outcome.output;
  const std::string page = testing::FreshDirectory("replay-bad-signal") + "/replay.html";
  const testing::Outcome replay =
      testing::Unimouse("replay " + out + " --html " + page + " --signal nonsense");
  EXPECT_EQ(replay.exit_code, 2) << replay.output;
  std::vector<std::string> naming;
  std::istringstream lines(replay.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("nonsense") != std::string::npos) naming.push_back(line);
  }
  ASSERT_EQ(naming.size(), 1u) << replay.output;
  EXPECT_NE(naming[0].find("--signal nonsense"), std::string::npos) << naming[0];
  EXPECT_FALSE(fs::exists(page));
}

// no browser: what the written file holds
TEST(ReplayPageTest, KeepsEveryTextOfTheDataInsideItsScriptElement) {
  json data = TestData();
  const std::string hostile =
      "</script><script>alert(1)</script><!-- \xE2\x80\xA8 \xE2\x80\xA9 </SCRIPT >";
  data["title"] = hostile;
  data["log"].push_back({{"t", 1}, {"level", 2}, {"name", "<b>"}, {"message", hostile}});
  data["hud"].push_back({{"t", 1}, {"lines", {"not UTF-8: \xC3\x28 \xFF"}}});
  const fs::path dir = testing::FreshDirectory("replay-file");
  const std::string path = (dir / "replay.html").string();
  WriteReplayPage(data, path);
  const std::string page = ReadTextFile(path);

  const std::string open = "<script type=\"application/json\" id=\"replay-data\">";
  const size_t start = page.find(open);
  ASSERT_NE(start, std::string::npos);
  const size_t body = start + open.size();
  const size_t end = page.find("</script>", body);
  ASSERT_NE(end, std::string::npos);
  const std::string inside = page.substr(body, end - body);
  EXPECT_EQ(inside.find('<'), std::string::npos);
  EXPECT_EQ(inside.find("\xE2\x80\xA8"), std::string::npos);
  EXPECT_EQ(inside.find("\xE2\x80\xA9"), std::string::npos);

  // what ends the element is the element's own end: the data in it is whole
  const json read = json::parse(inside);
  EXPECT_EQ(read["title"], hostile);
  EXPECT_EQ(read["log"].back()["message"], hostile);
  EXPECT_EQ(read["hud"].back()["lines"][0], "not UTF-8: \xEF\xBF\xBD( \xEF\xBF\xBD");
  EXPECT_EQ(read["robots"], data["robots"]);
  // the one other script is the page's own, and the title tag holds the title as text
  EXPECT_EQ(Count(page, "<script"), 2u);
  EXPECT_NE(page.find("<title>Replay: &lt;/script&gt;"), std::string::npos);
}

TEST(ReplayPageTest, ItsScriptAndStyleCannotEndTheirElements) {
  std::string script(ReplayPageScript()), style(ReplayPageStyle());
  for (std::string* text : {&script, &style}) {
    for (char& c : *text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  EXPECT_GT(script.size(), 1000u);
  EXPECT_EQ(script.find("</script"), std::string::npos);
  EXPECT_EQ(script.find("<!--"), std::string::npos);
  EXPECT_GT(style.size(), 1000u);
  EXPECT_EQ(style.find("</style"), std::string::npos);
  // and no address of anything to fetch
  for (const char* address : {"://", "url(", "@import"}) {
    EXPECT_EQ(script.find(address), std::string::npos) << address;
    EXPECT_EQ(style.find(address), std::string::npos) << address;
  }
}

TEST(ReplayPageTest, ThrowsNamingThePathWhenItCannotWrite) {
  const std::string path = testing::FreshDirectory("replay-missing") + "/no/such/dir/replay.html";
  try {
    WriteReplayPage(TestData(), path);
    FAIL() << "wrote " << path;
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind(path + ": ", 0), 0u) << error.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace unimouse
