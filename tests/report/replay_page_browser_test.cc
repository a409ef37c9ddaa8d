// SPDX-License-Identifier: GPL-3.0-or-later
// The replay page as a student sees it: loaded from a file into headless Chromium (Debian's
// `chromium`), its scripts run, the rendered DOM read back with --dump-dom and the drawing with
// --screenshot. The robot's place on the screenshot is checked against the circle the test
// itself drove it along.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "png_file.h"
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

// the path of `program` on PATH, or "" when none has it
std::string FindProgram(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path == nullptr ? "" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((dir + "/" + program).c_str(), X_OK) == 0) {
      return dir + "/" + program;
    }
  }
  return "";
}

// the value of attribute `name` in the first tag of `dom` that starts with `tag_start`
std::string AttributeOf(const std::string& dom, const std::string& tag_start,
                        const std::string& name) {
  const size_t tag = dom.find(tag_start);
  if (tag == std::string::npos) return "";
  const size_t end = dom.find('>', tag);
  const std::string marker = " " + name + "=\"";
  const size_t at = dom.find(marker, tag);
  if (at == std::string::npos || at > end) return "";
  const size_t start = at + marker.size();
  return dom.substr(start, dom.find('"', start) - start);
}

double NumberAttribute(const std::string& dom, const std::string& tag_start,
                       const std::string& name) {
  const std::string value = AttributeOf(dom, tag_start, name);
  EXPECT_FALSE(value.empty()) << tag_start << " has no " << name;
  return value.empty() ? NAN : std::stod(value);
}

size_t Count(const std::string& text, const std::string& part) {
  size_t count = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// the pixels of one colour in a screenshot: how many, their centroid (pixel centres, in page
// pixels) and the direction of their longer axis on screen (radians, y down, modulo pi)
struct Blob {
  double count = 0, x = 0, y = 0, axis = 0;
};

Blob FindColour(const std::vector<uint8_t>& rgb, int width, int height, int r, int g, int b) {
  constexpr int kTolerance = 4;
  Blob blob;
  double sum_xx = 0, sum_yy = 0, sum_xy = 0;
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const uint8_t* pixel = &rgb[3 * (static_cast<size_t>(row) * width + column)];
      if (std::abs(pixel[0] - r) > kTolerance || std::abs(pixel[1] - g) > kTolerance ||
          std::abs(pixel[2] - b) > kTolerance) {
        continue;
      }
      const double x = column + 0.5, y = row + 0.5;
      blob.count += 1;
      blob.x += x;
      blob.y += y;
      sum_xx += x * x;
      sum_yy += y * y;
      sum_xy += x * y;
    }
  }
  if (blob.count == 0) return blob;
  blob.x /= blob.count;
  blob.y /= blob.count;
  const double mu20 = sum_xx / blob.count - blob.x * blob.x;
  const double mu02 = sum_yy / blob.count - blob.y * blob.y;
  const double mu11 = sum_xy / blob.count - blob.x * blob.y;
  blob.axis = 0.5 * std::atan2(2 * mu11, mu20 - mu02);
  return blob;
}

class ReplayPageBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = FindProgram("chromium");
    if (chromium_.empty()) GTEST_SKIP() << "no chromium on PATH (Debian: apt-get install chromium)";
    dir_ = testing::FreshDirectory("replay");
    WriteReplayPage(TestData(), (dir_ / "replay.html").string());
  }

  // Chromium on `address` in a 1200 x 1000 window at one device pixel per CSS pixel
  testing::Outcome Chromium(const std::string& options, const std::string& address) {
    // --no-sandbox: the sandbox cannot start as root, and this page is our own file; the
    // profile and its caches stay in this test's directory. --hide-scrollbars: a screenshot
    // would have a scroll bar that --dump-dom has not, and lay the page out 15 px narrower
    const fs::path profile = dir_ / "chromium-profile";
    return testing::Shell("XDG_CONFIG_HOME=" + profile.string() +
                          " XDG_CACHE_HOME=" + profile.string() + " " + chromium_ +
                          " --headless --no-sandbox --disable-gpu --no-first-run "
                          "--force-device-scale-factor=1 --window-size=1200,1000 --hide-scrollbars "
                          "--user-data-dir=" +
                          profile.string() + " " + options + " '" + address + "' 2>/dev/null");
  }

  std::string PageAddress(const std::string& fragment) {
    return "file://" + (dir_ / "replay.html").string() + "#" + fragment;
  }

  // the page's DOM after its scripts ran, opened at `fragment`
  std::string RenderedDom(const std::string& fragment) {
    const testing::Outcome chromium = Chromium("--dump-dom", PageAddress(fragment));
    EXPECT_EQ(chromium.exit_code, 0);
    return chromium.output;
  }

  // robot 0's pose as the screenshot shows it at `fragment`, mapped to metres through the
  // scene's mapping that the same page gives in its DOM; `pixels_per_m` is that mapping's scale
  Blob RobotOnScreen(const std::string& fragment, Pose* shown, double* pixels_per_m) {
    const std::string dom = RenderedDom(fragment);
    EXPECT_NE(dom.find("data-ready=\"1\""), std::string::npos) << dom;
    const std::string canvas = "<canvas id=\"scene\"";
    const double left = NumberAttribute(dom, canvas, "data-page-left");
    const double top = NumberAttribute(dom, canvas, "data-page-top");
    const double origin_x = NumberAttribute(dom, canvas, "data-origin-x");
    const double origin_y = NumberAttribute(dom, canvas, "data-origin-y");
    *pixels_per_m = NumberAttribute(dom, canvas, "data-px-per-m");

    const std::string png = (dir_ / "screenshot.png").string();
    std::error_code ignored;
    fs::remove(png, ignored);
    EXPECT_EQ(Chromium("--screenshot=" + png, PageAddress(fragment)).exit_code, 0);
    int width = 0, height = 0;
    const std::vector<uint8_t> rgb = ReadPng(png, &width, &height);
    const Blob blob = FindColour(rgb, width, height, 0xe6, 0x00, 0x7e);
    // on screen y grows downward: north is up
    shown->x = (blob.x - left - origin_x) / *pixels_per_m;
    shown->y = (origin_y - (blob.y - top)) / *pixels_per_m;
    shown->yaw = -blob.axis;
    return blob;
  }

  std::string chromium_;
  fs::path dir_;
};

TEST_F(ReplayPageBrowserTest, DrawsRobot0WhereItsCircleHasItAtTheCursor) {
  // 3.1425 s is a quarter of the way between two samples whose yaws are either side of pi: the
  // long way round would turn the robot a quarter turn
  for (const double t : {2.345, 3.1425, 7.5}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    Pose shown;
    double pixels_per_m = 0;
    const Blob blob = RobotOnScreen("t=" + std::to_string(t), &shown, &pixels_per_m);
    const Pose expected = CirclePose(t);

    // all of its body but its edges and its heading mark, and nothing else in its colour
    const double area_px = kLength_m * kWidth_m * pixels_per_m * pixels_per_m;
    EXPECT_GT(blob.count, 0.8 * area_px);
    EXPECT_LT(blob.count, 1.02 * area_px);
    EXPECT_NEAR(shown.x, expected.x, 0.01);
    EXPECT_NEAR(shown.y, expected.y, 0.01);
    // its length lies along its heading (a rectangle's axis is known modulo a half turn)
    EXPECT_NEAR(std::remainder(shown.yaw - expected.yaw, std::numbers::pi), 0, 0.07);
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
  Chromium("--log-net-log=" + net_log + " --dump-dom", PageAddress("t=2&speed=2"));
  EXPECT_EQ(NetworkRequestsOfPages(net_log), std::vector<std::string>{});

  // the check sees a page's request: a page with an image from a server is caught
  std::ofstream(dir_ / "fetching.html") << "<!DOCTYPE html><img src=\"http://127.0.0.1:9/x.png\">";
  const std::string control_log = (dir_ / "control-net-log.json").string();
  Chromium("--log-net-log=" + control_log + " --dump-dom",
           "file://" + (dir_ / "fetching.html").string());
  EXPECT_EQ(NetworkRequestsOfPages(control_log),
            std::vector<std::string>{"http://127.0.0.1:9/x.png"});
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
