// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse run`'s pictures from the command line and from Lua: which files at which times and
// sizes, video, scenario events, and what happens on a machine that cannot draw. Tests that
// draw are skipped with the reason when no EGL display can be made.
#include <gtest/gtest.h>

#include <filesystem>

#include "egl_context.h"
#include "png_file.h"
#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

using testing::Unimouse;
using testing::UnimouseRun;

const std::string kTests = UNIMOUSE_SOURCE_DIR "/tests/scenarios/";
// glvnd finds no EGL driver at all: a machine without Mesa's EGL
const std::string kNoEgl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json ";

std::string Out(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

void SkipWithoutEgl() {
  try {
    EglContext::Create();
  } catch (const RenderUnavailable& e) {
    GTEST_SKIP() << "no offscreen rendering on this machine: " << e.what();
  }
}

void ExpectPng(const std::string& path, int width, int height) {
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  int w = 0, h = 0;
  ReadPng(path, &w, &h);
  EXPECT_EQ(w, width) << path;
  EXPECT_EQ(h, height) << path;
}

int CountFiles(const std::string& dir) {
  if (!std::filesystem::exists(dir)) return 0;
  return static_cast<int>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

TEST(PicturesTest, SnapshotsAtTheTimesAskedAndFramesAtTheRateAsked) {
  SkipWithoutEgl();
  const auto r = UnimouseRun(
      "--scenario none --maze japan2018 --duration 2 --snapshot-every 1s --snapshot-at 0.5 "
      "--snapshot-size "
      "320x240 --frames-fps 5 --snapshot-end --camera chase",
      "pictures_times");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const std::string out = Out("pictures_times");
  for (const char* t : {"0000.500", "0001.000", "0002.000"}) {
    ExpectPng(out + "/snapshots/" + t + "s.png", 320, 240);
  }
  EXPECT_EQ(CountFiles(out + "/snapshots"), 3);
  // frames at 0, 0.2, ..., 2.0 s
  EXPECT_EQ(CountFiles(out + "/frames"), 11);
  ExpectPng(out + "/frames/000010.png", 320, 240);
  ExpectPng(out + "/final.png", 320, 240);
  EXPECT_EQ(r.result["pictures"]["written"], 3 + 11 + 1);
}

TEST(PicturesTest, AFinalPictureWheneverTheMachineCanDraw) {
  SkipWithoutEgl();
  const auto r = UnimouseRun("--scenario none --maze japan2018 --duration 0.1", "pictures_default");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  ExpectPng(Out("pictures_default") + "/final.png", 640, 480);
  const auto none =
      UnimouseRun("--scenario none --maze japan2018 --duration 0.1 --no-pictures", "pictures_none");
  ASSERT_EQ(none.outcome.exit_code, 0) << none.outcome.output;
  EXPECT_FALSE(std::filesystem::exists(Out("pictures_none") + "/final.png"));
}

TEST(PicturesTest, WithoutEglAskedPicturesStopWithOneLineAndTheRestRuns) {
  const auto asked =
      UnimouseRun("--scenario none --maze japan2018 --duration 0.1 --snapshot-every 1s",
                  "pictures_noegl", kNoEgl);
  EXPECT_EQ(asked.outcome.exit_code, 2) << asked.outcome.output;
  EXPECT_NE(asked.outcome.output.find("unimouse: error: no EGL display"), std::string::npos)
      << asked.outcome.output;
  // a run that asked for none still runs, and says why it has no final picture
  const auto plain =
      UnimouseRun("--scenario none --maze japan2018 --duration 0.1", "pictures_noegl", kNoEgl);
  EXPECT_EQ(plain.outcome.exit_code, 0) << plain.outcome.output;
  EXPECT_NE(plain.outcome.output.find("no pictures: no EGL display"), std::string::npos);
  EXPECT_EQ(plain.result["status"], "completed");
  // a scenario's own pictures are skipped, and it hears why
  const auto lua = UnimouseRun("--scenario " + kTests + "pictures.lua", "pictures_noegl", kNoEgl);
  EXPECT_EQ(lua.outcome.exit_code, 1) << lua.outcome.output;
  EXPECT_NE(lua.result["scenario"]["reason"].get<std::string>().find("no EGL display"),
            std::string::npos);
}

TEST(PicturesTest, BadPictureOptionsAreBadInputWithAResultSayingSo) {
  for (const char* options :
       {"--snapshot-every fast", "--snapshot-at -1", "--snapshot-size 640", "--snapshot-size 9x9",
        "--camera side --snapshot-end", "--snapshot-on wall_contact"}) {
    const auto o =
        UnimouseRun(std::string("--maze none --duration 0.1 ") + options, "pictures_bad");
    EXPECT_EQ(o.outcome.exit_code, 2) << options << "\n" << o.outcome.output;
    ASSERT_TRUE(o.result.is_object()) << options;
    EXPECT_EQ(o.result["status"], "error") << options;
    EXPECT_EQ(o.result["exit_code"], 2) << options;
  }
  SkipWithoutEgl();
  const auto o = Unimouse("run --out " + Out("pictures_bad") + " --scenario " + kTests +
                          "pen.lua --snapshot-on bump");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--snapshot-on bump: not an event"), std::string::npos) << o.output;
}

TEST(PicturesTest, ScenarioSavesPicturesInsideItsOutputDirectoryOnly) {
  SkipWithoutEgl();
  const auto saved = UnimouseRun("--scenario " + kTests + "pictures.lua", "pictures_lua");
  ASSERT_EQ(saved.outcome.exit_code, 0) << saved.outcome.output;
  ExpectPng(Out("pictures_lua") + "/lua/start.png", 200, 100);
  const auto camera =
      UnimouseRun("--scenario " + kTests + "pictures.lua --set camera=side", "pictures_lua");
  EXPECT_EQ(camera.outcome.exit_code, 1);
  EXPECT_NE(camera.result["scenario"]["reason"].get<std::string>().find("unknown camera 'side'"),
            std::string::npos);
  // a script that writes outside is a script error, with its file and line
  const auto escape =
      UnimouseRun("--scenario " + kTests + "pictures.lua --set file=../escape.png", "pictures_lua");
  EXPECT_EQ(escape.outcome.exit_code, 3);
  EXPECT_NE(escape.outcome.output.find("pictures.lua:13:"), std::string::npos)
      << escape.outcome.output;
  EXPECT_FALSE(std::filesystem::exists(Out("escape.png")));
}

TEST(PicturesTest, APictureAtEveryScenarioEvent) {
  SkipWithoutEgl();
  // the pen: the robot drives into its arc once; the pictures take the camera and size asked
  const auto r = UnimouseRun("--scenario " + kTests +
                                 "pen.lua --snapshot-on wall_contact --snapshot-size 300x200 "
                                 "--camera chase",
                             "pictures_events");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  ExpectPng(Out("pictures_events") + "/events/wall_contact_0001.png", 300, 200);
  EXPECT_EQ(CountFiles(Out("pictures_events") + "/events"), 1);
}

TEST(PicturesTest, PicturesDoNotChangeTheRunAndRepeatWithIt) {
  SkipWithoutEgl();
  const std::string slalom = "--scenario slalom --controller " + kTests + "slalom_controller.lua";
  const std::string pictures =
      " --snapshot-every 0.5s --frames-fps 10 --camera chase --snapshot-end";
  const auto plain = UnimouseRun(slalom + " --no-pictures", "pictures_plain");
  const auto drawn = UnimouseRun(slalom + pictures, "pictures_drawn");
  const auto again = UnimouseRun(slalom + pictures, "pictures_again");
  ASSERT_EQ(plain.outcome.exit_code, 0) << plain.outcome.output;
  ASSERT_EQ(drawn.outcome.exit_code, 0) << drawn.outcome.output;
  EXPECT_GT(drawn.result["pictures"]["written"].get<int>(), 20);
  EXPECT_EQ(plain.result["robot_pose"], drawn.result["robot_pose"]);
  EXPECT_EQ(plain.result["sim_time_s"], drawn.result["sim_time_s"]);
  EXPECT_EQ(plain.result["scenario"], drawn.result["scenario"]);
  // the same seed, the same pictures, byte for byte
  for (const char* file : {"final.png", "frames/000010.png", "snapshots/0001.000s.png"}) {
    EXPECT_EQ(ReadTextFile(Out("pictures_drawn") + "/" + file),
              ReadTextFile(Out("pictures_again") + "/" + file))
        << file;
  }
}

bool HaveFfmpeg() { return std::system("ffmpeg -version > /dev/null 2>&1") == 0; }

TEST(PicturesTest, VideoOfTheRunThroughFfmpeg) {
  SkipWithoutEgl();
  if (!HaveFfmpeg()) GTEST_SKIP() << "ffmpeg is not installed";
  const auto r = UnimouseRun(
      "--scenario none --maze japan2018 --duration 1 --video run.mp4 --video-fps 10 "
      "--snapshot-size 160x120",
      "pictures_video");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const std::string video = Out("pictures_video") + "/run.mp4";
  ASSERT_TRUE(std::filesystem::exists(video));
  // frames at 0, 0.1, ..., 1.0 s
  const std::string count = Out("pictures_video") + "/frames.txt";
  ASSERT_EQ(std::system(("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                         "stream=nb_read_frames,width,height -of csv=p=0 " +
                         video + " > " + count)
                            .c_str()),
            0);
  std::FILE* f = std::fopen(count.c_str(), "r");
  int width = 0, height = 0, frames = 0;
  ASSERT_EQ(std::fscanf(f, "%d,%d,%d", &width, &height, &frames), 3);
  std::fclose(f);
  EXPECT_EQ(width, 160);
  EXPECT_EQ(height, 120);
  EXPECT_EQ(frames, 11);
}

TEST(PicturesTest, VideoWithoutFfmpegIsBadInput) {
  // an empty PATH: no ffmpeg to be found
  const auto r = UnimouseRun("--maze none --duration 0.1 --video run.mp4", "pictures_noffmpeg",
                             "PATH=/nonexistent ");
  EXPECT_EQ(r.outcome.exit_code, 2) << r.outcome.output;
  EXPECT_NE(r.outcome.output.find("--video needs ffmpeg"), std::string::npos) << r.outcome.output;
}

}  // namespace
}  // namespace unimouse
