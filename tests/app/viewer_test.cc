// SPDX-License-Identifier: GPL-3.0-or-later
// The live viewer: what its keys do, and the window itself under a virtual X server (Xvfb),
// skipped with the reason when xvfb-run is not installed.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "png_file.h"
#include "run_program.h"
#include "scene_renderer.h"
#include "text_file.h"
#include "viewer_controls.h"

namespace unimouse {
namespace {

TEST(ViewerControlsTest, KeysPauseStepAndChangeSpeed) {
  ViewerControls c;
  EXPECT_TRUE(c.Key(GLFW_KEY_SPACE));
  EXPECT_TRUE(c.paused);
  EXPECT_TRUE(c.Key(GLFW_KEY_SPACE));
  EXPECT_FALSE(c.paused);
  // a step pauses and asks for one tick each press
  c.Key(GLFW_KEY_RIGHT);
  c.Key(GLFW_KEY_N);
  EXPECT_TRUE(c.paused);
  EXPECT_EQ(c.steps_wanted, 2);
  for (int i = 0; i < 10; ++i) c.Key(GLFW_KEY_EQUAL);
  EXPECT_EQ(c.speed, ViewerControls::kMaxSpeed);
  c.Key(GLFW_KEY_0);
  EXPECT_EQ(c.speed, 1);
  c.Key(GLFW_KEY_MINUS);
  EXPECT_EQ(c.speed, 0.5);
  for (int i = 0; i < 10; ++i) c.Key(GLFW_KEY_MINUS);
  EXPECT_EQ(c.speed, ViewerControls::kMinSpeed);
}

TEST(ViewerControlsTest, TabFollowsTheNextRobot) {
  ViewerControls c;
  EXPECT_FALSE(c.follow);
  c.Key(GLFW_KEY_TAB);
  EXPECT_TRUE(c.follow);
  EXPECT_EQ(c.followed, 1);
  c.Key(GLFW_KEY_TAB);
  EXPECT_EQ(c.followed, 2);  // the viewer counts it on through the run's robots
  c.Key(GLFW_KEY_F);
  EXPECT_FALSE(c.follow);
}

TEST(ViewerControlsTest, KeysToggleWhatIsShown) {
  ViewerControls c;
  c.Key(GLFW_KEY_R);
  c.Key(GLFW_KEY_B);
  c.Key(GLFW_KEY_U);
  c.Key(GLFW_KEY_F);
  c.Key(GLFW_KEY_H);
  EXPECT_FALSE(c.beams);
  EXPECT_FALSE(c.beliefs);
  EXPECT_FALSE(c.hud);
  EXPECT_TRUE(c.follow);
  EXPECT_TRUE(c.help);
  c.Key(GLFW_KEY_2);
  EXPECT_EQ(c.preset, "chase");
  c.Key(GLFW_KEY_BACKSPACE);
  EXPECT_TRUE(c.restart);
  c.Key(GLFW_KEY_ESCAPE);
  EXPECT_TRUE(c.quit);
  EXPECT_FALSE(c.Key(GLFW_KEY_Z));
}

TEST(ViewerControlsTest, TheFrameRateCountsTheGapsBetweenFrames) {
  EXPECT_DOUBLE_EQ(FrameRate(31, 1.0), 30);  // 31 frames, 30 gaps, in one second
  EXPECT_DOUBLE_EQ(FrameRate(2, 0.025), 40);
  EXPECT_EQ(FrameRate(1, 0), 0);  // one frame has no rate
  EXPECT_EQ(FrameRate(0, 0), 0);
  EXPECT_EQ(FrameRate(5, 0), 0);  // no time between them: none measured
}

TEST(ViewerTest, KnowsMesasSoftwareRasterisersByTheirRendererNames) {
  EXPECT_TRUE(IsSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(IsSoftwareRenderer("softpipe"));
  EXPECT_TRUE(IsSoftwareRenderer("Software Rasterizer (swrast)"));
  EXPECT_FALSE(IsSoftwareRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
  EXPECT_FALSE(IsSoftwareRenderer("NVIDIA GeForce RTX 3060/PCIe/SSE2"));
  EXPECT_FALSE(IsSoftwareRenderer("AMD Radeon RX 6600 (navi23, LLVM 15.0.6, DRM 3.49)"));
  EXPECT_FALSE(IsSoftwareRenderer(nullptr));
}

TEST(ViewerTest, OpensUnderXvfbDrawsFramesAndItsScreenshotShowsTheMaze) {
  if (!testing::HaveXvfbRun()) GTEST_SKIP() << "xvfb-run is not installed (apt install xvfb xauth)";
  const auto r = testing::UnimouseRun(
      "--scenario none --maze japan2018 --duration 5 --view --view-frames 30 --no-pictures",
      "viewer_xvfb", testing::OnVirtualDisplay());
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  EXPECT_EQ(r.result["view"]["frames"], 30);
  // the frames were drawn within the run: from the first to the last takes no longer than it
  const double fps = r.result["view"]["frames_per_second"].get<double>();
  ASSERT_GT(fps, 0);
  EXPECT_LE(29 / fps, r.result["wall_time_s"].get<double>());
  EXPECT_NE(r.outcome.output.find("  viewer: 30 frames, "), std::string::npos) << r.outcome.output;
  EXPECT_GT(r.result["sim_time_s"].get<double>(), 0);
  const std::string shot =
      (std::filesystem::temp_directory_path() / "viewer_xvfb/view.png").string();
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(shot, &width, &height);
  EXPECT_EQ(width, 1200);
  EXPECT_EQ(height, 900);
  // not blank: white walls, red posts, the dark floor, the text of the overlays
  std::set<uint32_t> colours;
  int white = 0;
  for (size_t i = 0; i < rgb.size(); i += 3) {
    colours.insert(rgb[i] << 16 | rgb[i + 1] << 8 | rgb[i + 2]);
    white += rgb[i] > 200 && rgb[i + 1] > 200 && rgb[i + 2] > 200;
  }
  EXPECT_GT(colours.size(), 100u);
  EXPECT_GT(white, 5000);
}

TEST(ViewerTest, AnMmsProgramOnTheRobotIsShownUntilTheWindowClosesWhichInterruptsTheRun) {
  if (!testing::HaveXvfbRun()) GTEST_SKIP() << "xvfb-run is not installed (apt install xvfb xauth)";
  const std::string out = (std::filesystem::temp_directory_path() / "viewer_mms").string();
  const auto o =
      testing::Unimouse("mms --physical --maze japan2018 --view --view-frames 20 --out " + out +
                            " -- " UNIMOUSE_MMS_FLOODFILL,
                        testing::OnVirtualDisplay());
  // the run goes at real time while the window is open: 20 frames are some seconds of it
  EXPECT_EQ(o.exit_code, 3) << o.output;
  const nlohmann::json r = nlohmann::json::parse(ReadTextFile(out + "/result.json"));
  EXPECT_EQ(r["status"], "interrupted");
  EXPECT_NE(r["reason"].get<std::string>().find("the viewer's window was closed"),
            std::string::npos)
      << r["reason"];
  const double sim_s = r["physical"]["sim_time_s"].get<double>();
  EXPECT_GT(sim_s, 0.2);
  EXPECT_LT(sim_s, 30);
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(out + "/view.png", &width, &height);
  EXPECT_EQ(width, 1200);
  EXPECT_EQ(height, 900);
  // the client colours each cell it stands on cyan ('c'): the start cell's tile is in the window
  int cyan = 0;
  for (size_t i = 0; i < rgb.size(); i += 3) {
    cyan += rgb[i + 1] > rgb[i] + 60 && rgb[i + 2] > rgb[i] + 60;
  }
  EXPECT_GT(cyan, 100);
}

// an X server of its own, which the test then takes away while the window shows a long run
TEST(ViewerTest, ADisplayThatGoesAwayEndsTheRunWithItsResultAndExitCode3) {
  if (std::system("command -v Xvfb > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "Xvfb is not installed (apt install xvfb)";
  }
  const std::string out = testing::FreshDirectory("viewer_display_lost");
  // -displayfd: the server picks a free display and says which
  const std::string script =
      "exec 3>" + out +
      "/display; Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp "
      "2>/dev/null & server=$!; "
      "for i in $(seq 100); do [ -s " +
      out +
      "/display ] && break; sleep 0.1; done; "
      // what the window held lives with the display that went away and is not freed: the
      // sanitizer build's leak check at exit would count it and change the exit code
      "DISPLAY=:$(cat " +
      out +
      "/display) ASAN_OPTIONS=detect_leaks=0 " UNIMOUSE_BINARY
      " run --scenario none --maze none --duration 100000 --view --no-pictures --out " +
      out +
      "/run & run=$!; "
      // the run's log exists once the window is open and the run assembled
      "for i in $(seq 300); do [ -e " +
      out +
      "/run/log.txt ] && break; sleep 0.1; done; "
      "sleep 1; kill $server; wait $run; echo \"exit code $?\"";
  const testing::Outcome o = testing::Shell("sh -c '" + script + "'");
  EXPECT_NE(o.output.find("exit code 3"), std::string::npos) << o.output;
  const nlohmann::json result = nlohmann::json::parse(ReadTextFile(out + "/run/result.json"));
  EXPECT_EQ(result["exit_code"], 3) << result.dump(1);
  EXPECT_NE(result.dump().find("the viewer's display went away"), std::string::npos)
      << result.dump(1);
}

TEST(ViewerTest, WithoutADisplayItIsBadInput) {
  const auto r =
      testing::Unimouse("run --maze none --duration 0.1 --view --out " +
                            (std::filesystem::temp_directory_path() / "viewer_nodisplay").string(),
                        "env -u DISPLAY -u WAYLAND_DISPLAY ");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--view needs a display"), std::string::npos) << r.output;
}

TEST(ViewerTest, WithoutADisplayAnMmsRunIsBadInputAndSaysSoInItsResult) {
  const std::string out =
      (std::filesystem::temp_directory_path() / "viewer_mms_nodisplay").string();
  const auto r = testing::Unimouse(
      "mms --physical --view --maze japan2018 --out " + out + " -- " UNIMOUSE_MMS_FLOODFILL,
      "env -u DISPLAY -u WAYLAND_DISPLAY ");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const nlohmann::json result = nlohmann::json::parse(ReadTextFile(out + "/result.json"));
  EXPECT_EQ(result["status"], "error");
  EXPECT_EQ(result["reason"].get<std::string>().rfind("--view needs a display", 0), 0u)
      << result["reason"];
}

}  // namespace
}  // namespace unimouse
