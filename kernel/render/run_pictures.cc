// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_pictures.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>

#include "png_file.h"
#include "unimouse/errors.h"
#include "unimouse/plugin_abi.h"

namespace unimouse {
namespace {

bool OnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  const std::string dirs = path;
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string file = dirs.substr(start, end - start) + "/" + program;
    if (end > start && ::access(file.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

std::string ShellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// the offscreen context, current while a picture is drawn
struct ScopedCurrent {
  explicit ScopedCurrent(const EglContext& c) : context(c) { context.MakeCurrent(); }
  ~ScopedCurrent() { context.Release(); }
  const EglContext& context;
};

// the step at which sim time t is reached
int64_t StepAt(double t_s, double timestep_s) { return std::llround(t_s / timestep_s); }

}  // namespace

RunPictures::RunPictures(Kernel& kernel, PictureOptions options, const FirmwareBeliefs* beliefs,
                         std::string out_dir)
    : kernel_(kernel),
      options_(std::move(options)),
      out_dir_(std::move(out_dir)),
      beliefs_(beliefs) {
  const PictureOptions& o = options_;
  const double dt = kernel.timestep_s();
  UNIMOUSE_THROW_UNLESS(o.width >= 16 && o.height >= 16 && o.width <= SceneRenderer::kMaxWidth &&
                            o.height <= SceneRenderer::kMaxHeight,
                        "--snapshot-size is 16x16 to " + std::to_string(SceneRenderer::kMaxWidth) +
                            "x" + std::to_string(SceneRenderer::kMaxHeight) + " pixels");
  UNIMOUSE_THROW_UNLESS(o.every_s >= 0 && std::isfinite(o.every_s),
                        "--snapshot-every must be a positive number of seconds");
  if (o.every_s > 0) every_steps_ = std::max<int64_t>(1, StepAt(o.every_s, dt));
  for (double t : o.at_s) {
    UNIMOUSE_THROW_UNLESS(t >= 0 && std::isfinite(t), "--snapshot-at must be a sim time >= 0 s");
    at_steps_.push_back(std::max<int64_t>(1, StepAt(t, dt)));
  }
  UNIMOUSE_THROW_UNLESS(
      o.frames_fps >= 0 && o.frames_fps <= 1000 && o.video_fps > 0 && o.video_fps <= 1000,
      "--frames-fps and --video-fps are 1 to 1000 frames a second");
  if (!o.video.empty()) {
    UNIMOUSE_THROW_UNLESS(o.width % 2 == 0 && o.height % 2 == 0,
                          "--video needs an even width and height");
    UNIMOUSE_THROW_UNLESS(OnPath("ffmpeg"),
                          "--video needs ffmpeg, which is not installed (apt install ffmpeg); "
                          "--frames-fps writes the frames as PNG files instead");
  }
  CheckCameraName(o.camera);
  // ask now, so that a machine that cannot draw says so before the run, not after it
  if (o.Any()) MakeRenderer();
}

void RunPictures::MakeRenderer() {
  egl_ = EglContext::Create();
  renderer_ = std::make_unique<SceneRenderer>(kernel_);
  renderer_name_ = egl_->renderer();
  egl_->Release();
}

RunPictures::~RunPictures() {
  if (ffmpeg_ != nullptr) pclose(ffmpeg_);
  if (!egl_) return;
  egl_->MakeCurrent();  // the renderer's GL objects go with their own context
  renderer_.reset();
}

bool RunPictures::EnsureRenderer() {
  if (renderer_) return true;
  if (!unavailable_.empty()) return false;
  try {
    MakeRenderer();
  } catch (const RenderUnavailable& e) {
    unavailable_ = e.what();
    kernel_.Log(UNIMOUSE_LOG_WARNING, "pictures", unavailable_ + "; pictures are skipped");
    return false;
  }
  return true;
}

Image RunPictures::Take(const std::string& camera, int width, int height) {
  DrawOptions draw;
  if (hud_) draw.hud = hud_();
  draw.firmware = beliefs_;
  const ScopedCurrent current(*egl_);
  return renderer_->Snapshot(width, height, camera, draw);
}

std::string RunPictures::Write(const std::string& relative, const std::string& camera, int width,
                               int height) {
  // a picture that cannot be taken is reported, never the end of the run
  try {
    const std::filesystem::path path = std::filesystem::path(out_dir_) / relative;
    std::error_code ignored;
    std::filesystem::create_directories(path.parent_path(), ignored);
    const Image image = Take(camera, width, height);
    WritePng(path.string(), image.width, image.height, image.rgb);
    ++written_;
    return "";
  } catch (const InputError& e) {
    kernel_.Log(UNIMOUSE_LOG_WARNING, "pictures", e.what());
    return e.what();
  }
}

std::string RunPictures::Save(const std::string& file, const std::string& camera, int width,
                              int height) {
  return EnsureRenderer() ? Write(file, camera, width, height) : unavailable_;
}

void RunPictures::AfterStep() {
  if (!renderer_) return;
  const PictureOptions& o = options_;
  const int64_t step = kernel_.state().step();
  const double t = kernel_.state().data().time;
  char name[64];
  const bool due_every = every_steps_ > 0 && step % every_steps_ == 0;
  const bool due_at = std::find(at_steps_.begin(), at_steps_.end(), step) != at_steps_.end();
  if (due_every || due_at) {
    std::snprintf(name, sizeof(name), "snapshots/%08.3fs.png", t);
    Write(name, o.camera, o.width, o.height);
  }
  // frames at k / fps of sim time, the first at the first step
  if (o.frames_fps > 0 && t + 1e-9 >= next_frame_s_) {
    std::snprintf(name, sizeof(name), "frames/%06d.png", frame_++);
    Write(name, o.camera, o.width, o.height);
    next_frame_s_ = frame_ / o.frames_fps;
  }
  if (!o.video.empty() && t + 1e-9 >= next_video_s_) {
    if (ffmpeg_ == nullptr) {
      const std::string command =
          "ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " +
          std::to_string(o.width) + "x" + std::to_string(o.height) + " -r " +
          std::to_string(o.video_fps) + " -i - -c:v libx264 -pix_fmt yuv420p " +
          ShellQuoted((std::filesystem::path(out_dir_) / o.video).string());
      std::signal(SIGPIPE, SIG_IGN);  // an encoder that dies must not take the run with it
      ffmpeg_ = popen(command.c_str(), "w");
      UNIMOUSE_DEMAND(ffmpeg_ != nullptr);
    }
    const Image image = Take(o.camera, o.width, o.height);
    if (std::fwrite(image.rgb.data(), 1, image.rgb.size(), ffmpeg_) != image.rgb.size()) {
      kernel_.Log(UNIMOUSE_LOG_WARNING, "pictures",
                  "ffmpeg stopped taking frames; " + o.video + " ends here");
      pclose(ffmpeg_);
      ffmpeg_ = nullptr;
      options_.video.clear();
      return;
    }
    ++video_frames_;
    next_video_s_ = video_frames_ / o.video_fps;
  }
}

void RunPictures::Finish() {
  if (ffmpeg_ != nullptr) {
    const int status = pclose(ffmpeg_);
    ffmpeg_ = nullptr;
    if (status != 0) {
      kernel_.Log(UNIMOUSE_LOG_WARNING, "pictures",
                  "ffmpeg failed to write " + options_.video + " (exit status " +
                      std::to_string(status) + ")");
    } else {
      ++written_;
    }
  }
  if (options_.at_end && renderer_)
    Write("final.png", options_.camera, options_.width, options_.height);
}

}  // namespace unimouse
