// SPDX-License-Identifier: GPL-3.0-or-later
// The pictures a run takes: snapshots every so often, at chosen times and at the end, a frame
// sequence and an MP4 video, and pictures a scenario asks for (sim.snapshot_save). Files go to
// the run's output directory: snapshots/<time>s.png, frames/<n>.png, final.png.
//
// The offscreen context is made when the run starts if an option asks for pictures, so that a
// machine without EGL refuses at once (RenderUnavailable, exit code 2); a scenario's pictures
// alone make it on first use, and without EGL they are skipped with a warning.
#ifndef UNIMOUSE_RENDER_RUN_PICTURES_H_
#define UNIMOUSE_RENDER_RUN_PICTURES_H_

#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "egl_context.h"
#include "firmware_beliefs.h"
#include "kernel.h"
#include "scene_renderer.h"

namespace unimouse {

struct PictureOptions {
  std::string camera = "top";
  int width = 640;
  int height = 480;
  double every_s = 0;        ///< a snapshot every so many sim seconds; 0 for none
  std::vector<double> at_s;  ///< snapshots at these sim times
  bool at_end = false;       ///< final.png when the run ends
  double frames_fps = 0;     ///< frames/NNNNNN.png at this rate of sim time; 0 for none
  std::string video;         ///< an MP4 of the run, through ffmpeg; "" for none
  double video_fps = 30;
  bool required = false;  ///< make the context at the start even if only the scenario draws
  /// Whether any picture is asked for, so that the context is made at the start.
  bool Any() const {
    return required || every_s > 0 || !at_s.empty() || at_end || frames_fps > 0 || !video.empty();
  }
};

class RunPictures {
 public:
  /// Makes the offscreen context now if `options` asks for any picture; throws RenderUnavailable
  /// or InputError (bad size, camera or time, no ffmpeg for a video).
  /// `beliefs`, if given, are drawn: what the firmware reported of the maze.
  RunPictures(Kernel& kernel, PictureOptions options, const FirmwareBeliefs* beliefs,
              std::string out_dir);
  ~RunPictures();

  /// The HUD lines to draw, read at each picture.
  void SetHudSource(std::function<std::vector<std::string>()> hud) { hud_ = std::move(hud); }

  /// Takes the pictures due at the current step; call after every step.
  void AfterStep();
  /// Takes the final picture and closes the video; call once when the run is over.
  void Finish();

  /// Saves a picture now as `file` in the output directory; returns "" or why it could not.
  std::string Save(const std::string& file, const std::string& camera, int width, int height);

  /// Pictures written so far, and the renderer's name ("" when none was made).
  int written() const { return written_; }
  const std::string& renderer() const { return renderer_name_; }

 private:
  void MakeRenderer();    // throws RenderUnavailable
  bool EnsureRenderer();  // false when the machine cannot draw (warned once)
  std::string Write(const std::string& relative, const std::string& camera, int width, int height);
  Image Take(const std::string& camera, int width, int height);

  Kernel& kernel_;
  PictureOptions options_;
  std::string out_dir_;
  std::function<std::vector<std::string>()> hud_;
  const FirmwareBeliefs* beliefs_;
  std::unique_ptr<EglContext> egl_;
  std::unique_ptr<SceneRenderer> renderer_;
  std::string renderer_name_;
  std::string unavailable_;  // why there is no renderer, once tried
  std::vector<int64_t> at_steps_;
  int64_t every_steps_ = 0;
  double next_frame_s_ = 0;
  int frame_ = 0;
  double next_video_s_ = 0;
  int video_frames_ = 0;
  std::FILE* ffmpeg_ = nullptr;
  int written_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RENDER_RUN_PICTURES_H_
