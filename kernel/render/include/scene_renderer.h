// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures of a run: the physics model's floor and robot, the scenery models' walls and posts
// (see world.h), the ToF beams (green on a hit, red on a miss, as in the original), what the
// firmware (or an mms program) believes about the maze (walls, visited cells, its path, cell
// colours as floor tiles, cell texts as labels), and the scenario's HUD, drawn with MuJoCo's
// renderer into the current OpenGL context (an EglContext offscreen, or the viewer's window).
//
// The renderer draws from its own copy of the model and data, so drawing never touches the
// state of the run: a run with pictures is the same run, bit for bit, as one without.
#ifndef UNIMOUSE_RENDER_SCENE_RENDERER_H_
#define UNIMOUSE_RENDER_SCENE_RENDERER_H_

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "firmware_beliefs.h"
#include "kernel.h"

namespace unimouse {

/// The named cameras: "top" looks straight down on the whole scene with north up, "chase"
/// follows behind the robot, "free" looks over the scene from the south-west.
inline constexpr const char* kCameraNames[] = {"top", "chase", "free"};
/// Throws InputError unless `name` is one of them.
void CheckCameraName(const std::string& name);

/// What goes into a picture besides the scene itself.
struct DrawOptions {
  bool beams = true;
  bool beliefs = true;           ///< what the firmware reported on its debug channels
  std::vector<std::string> hud;  ///< lines at the top left
  bool clock = true;             ///< the sim time at the bottom left
  const FirmwareBeliefs* firmware = nullptr;
};

/// Whether an OpenGL renderer's name (GL_RENDERER) is one of Mesa's software rasterisers, on
/// which the viewers' windows draw without multisampling.
bool IsSoftwareRenderer(const char* gl_renderer);

/// An RGB picture, rows from the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;
};

class SceneRenderer {
 public:
  /// The largest offscreen picture.
  static constexpr int kMaxWidth = 1920;
  static constexpr int kMaxHeight = 1080;

  /// Uploads the kernel's model to the OpenGL context current on this thread. Text is drawn at
  /// `font_scale` (an mjtFontScale): 100 suits pictures of 640x480, 150 a large window.
  SceneRenderer(const Kernel& kernel, int font_scale = mjFONTSCALE_100);
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;
  ~SceneRenderer();

  /// Returns a named camera for the kernel's current state and a viewport's width/height.
  /// Throws InputError for an unknown name.
  mjvCamera Camera(const std::string& name, double aspect) const;

  /// Draws the kernel's current state into `viewport` of the current framebuffer.
  void Draw(const mjrRect& viewport, const mjvCamera& camera, const DrawOptions& options);

  /// Draws offscreen and reads the picture back. Throws InputError for a size over the maximum.
  Image Snapshot(int width, int height, const std::string& camera, const DrawOptions& options);

  /// Reads a viewport of the current framebuffer back as a picture.
  Image Read(const mjrRect& viewport);

  /// Moves a camera as a mouse drag or scroll does (mjtMouse action; dx, dy in viewport
  /// heights).
  void MoveCamera(int action, double dx, double dy, mjvCamera* camera);

  mjrContext& context() { return context_; }
  const mjModel& model() const { return *model_; }

 private:
  void MakeContext(int width, int height);
  void CopyState();
  void AddBeams();
  void AddBeliefs(const FirmwareBeliefs& beliefs);
  mjvGeom* NewGeom();

  const Kernel& kernel_;
  int font_scale_;
  mjModel* model_ = nullptr;  // a copy of the physics model, with a larger offscreen buffer
  mjData* data_ = nullptr;
  std::vector<mjData*> scenery_data_;  // one for each of the world's scenery chunks
  mjvScene scene_;
  mjvOption option_;
  mjvPerturb perturb_;
  mjrContext context_;
  std::array<double, 2> scene_min_{};  // the scenery's extent on the floor
  std::array<double, 2> scene_max_{};
};

}  // namespace unimouse

#endif  // UNIMOUSE_RENDER_SCENE_RENDERER_H_
