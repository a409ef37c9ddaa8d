// SPDX-License-Identifier: GPL-3.0-or-later
#include "scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "mujoco_guard.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

constexpr double kBeamRadius_m = 0.003;
constexpr float kHit[4] = {0.1f, 0.95f, 0.2f, 1};
constexpr float kMiss[4] = {0.95f, 0.15f, 0.1f, 1};
constexpr float kBelievedWall[4] = {0.2f, 0.55f, 1, 1};
constexpr float kVisited[4] = {0.2f, 0.8f, 0.9f, 0.35f};
constexpr float kPlannedPath[4] = {1, 0.85f, 0.1f, 1};
// the scene's geoms beyond the models' own: beams, and beliefs about a 32x32 maze at most
constexpr int kExtraGeoms = 8 + 32 * 32 * 8;

// a parameter's declared default, as the component's type gives it
}  // namespace

void CheckCameraName(const std::string& name) {
  for (const char* known : kCameraNames) {
    if (name == known) return;
  }
  throw InputError("unknown camera '" + name + "': top, chase or free");
}

bool IsSoftwareRenderer(const char* gl_renderer) {
  if (gl_renderer == nullptr) return false;
  const std::string name = gl_renderer;
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "SWR"}) {
    if (name.find(software) != std::string::npos) return true;
  }
  return false;
}

SceneRenderer::SceneRenderer(const Kernel& kernel, int font_scale)
    : kernel_(kernel), font_scale_(font_scale) {
  mjv_defaultScene(&scene_);
  GuardMujoco([&] {
    model_ = mj_copyModel(nullptr, &kernel.mj_model());
    model_->vis.quality.shadowsize = 1;  // no shadows (below): no 64 MB shadow map either
    data_ = mj_makeData(model_);
    int scenery_geoms = 0;
    for (const World::SceneryChunk& chunk : kernel.world().scenery_chunks()) {
      scenery_data_.push_back(mj_makeData(chunk.model.get()));
      mj_kinematics(chunk.model.get(), scenery_data_.back());
      scenery_geoms += chunk.model->ngeom;
    }
    mjv_makeScene(model_, &scene_, model_->ngeom + scenery_geoms + kExtraGeoms);
  });
  mjv_defaultOption(&option_);
  // the light is straight above, so shadows add little to a picture and cost a software
  // renderer 40 ms of a 640x480 picture's 70 (docs/performance.md)
  scene_.flags[mjRND_SHADOW] = 0;
  mjv_defaultPerturb(&perturb_);
  mjr_defaultContext(&context_);
  MakeContext(640, 480);

  // the scene's extent, for the cameras that show all of it
  const auto& boxes = kernel.world().scenery();
  if (boxes.empty()) {
    const Pose2D p = kernel.world().spawn();
    scene_min_ = {p.x_m - 0.5, p.y_m - 0.5};
    scene_max_ = {p.x_m + 0.5, p.y_m + 0.5};
  } else {
    scene_min_ = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    scene_max_ = {-scene_min_[0], -scene_min_[1]};
    for (const StaticBox& b : boxes) {
      const double r = std::hypot(b.half_m[0], b.half_m[1]);
      for (int i = 0; i < 2; ++i) {
        scene_min_[i] = std::min(scene_min_[i], b.center_m[i] - r);
        scene_max_[i] = std::max(scene_max_[i], b.center_m[i] + r);
      }
    }
  }
}

SceneRenderer::~SceneRenderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
  for (mjData* d : scenery_data_) mj_deleteData(d);
  mj_deleteData(data_);
  mj_deleteModel(model_);
}

void SceneRenderer::MakeContext(int width, int height) {
  // the offscreen buffer is as large as the largest picture asked for: every picture clears and
  // resolves all of it, so a 1920x1080 buffer makes a 640x480 picture four times slower
  mjr_freeContext(&context_);
  model_->vis.global.offwidth = width;
  model_->vis.global.offheight = height;
  GuardMujoco([&] { mjr_makeContext(model_, &context_, font_scale_); });
}

mjvCamera SceneRenderer::Camera(const std::string& name, double aspect) const {
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  cam.type = mjCAMERA_FREE;
  const double cx = (scene_min_[0] + scene_max_[0]) / 2, cy = (scene_min_[1] + scene_max_[1]) / 2;
  const double hx = (scene_max_[0] - scene_min_[0]) / 2, hy = (scene_max_[1] - scene_min_[1]) / 2;
  const double tan_half_fovy = std::tan(model_->vis.global.fovy / 2 * std::numbers::pi / 180);
  if (name == "top") {
    // the whole scene with a small margin; walls are 5 cm tall, so the camera sits that much
    // higher than the floor's fit. In a picture wider than the scene, the scene goes to the
    // right, leaving the left side to the HUD.
    const double half_height_m = std::max(hy, hx / aspect) + 0.05;
    cam.lookat[0] = cx + hx + 0.05 - half_height_m * aspect;
    cam.lookat[1] = cy;
    cam.lookat[2] = 0;
    cam.distance = half_height_m / tan_half_fovy + 0.05;
    cam.azimuth = 90;  // north up
    cam.elevation = -90;
  } else if (name == "chase") {
    const Pose2D p = kernel_.world().RobotPose(kernel_.state().data());
    cam.lookat[0] = p.x_m;
    cam.lookat[1] = p.y_m;
    cam.lookat[2] = 0.03;
    cam.distance = 0.5;
    cam.azimuth = p.yaw_rad * 180 / std::numbers::pi;
    cam.elevation = -30;
  } else if (name == "free") {
    cam.lookat[0] = cx;
    cam.lookat[1] = cy;
    cam.lookat[2] = 0;
    cam.distance = 1.6 * std::max(hx, hy) / tan_half_fovy;
    cam.azimuth = 45;  // from the south-west
    cam.elevation = -40;
  } else {
    CheckCameraName(name);  // throws
  }
  return cam;
}

void SceneRenderer::CopyState() {
  const mjData& d = kernel_.state().data();
  data_->time = d.time;
  mju_copy(data_->qpos, d.qpos, model_->nq);
  mju_copy(data_->qvel, d.qvel, model_->nv);
  GuardMujoco([&] {
    mj_kinematics(model_, data_);
    mj_comPos(model_, data_);
    mj_camlight(model_, data_);
  });
}

mjvGeom* SceneRenderer::NewGeom() {
  if (scene_.ngeom >= scene_.maxgeom) return nullptr;
  mjvGeom* g = scene_.geoms + scene_.ngeom;
  g->segid = scene_.ngeom++;
  return g;
}

void SceneRenderer::AddBeams() {
  const std::vector<double>& signals = kernel_.state().signals();
  // every beam a component declared at bind, whatever its type
  for (const BeamSpec& b : kernel_.model().beams) {
    mjvGeom* g = NewGeom();
    if (g == nullptr) return;
    const BeamLine line = BeamLineOf(b, *data_, signals);
    mjv_initGeom(g, mjGEOM_CAPSULE, nullptr, nullptr, nullptr, line.hit ? kHit : kMiss);
    mjv_makeConnector(g, mjGEOM_CAPSULE, kBeamRadius_m, line.from_m[0], line.from_m[1],
                      line.from_m[2], line.to_m[0], line.to_m[1], line.to_m[2]);
    g->category = mjCAT_DECOR;
    g->emission = 0.8f;
  }
}

void SceneRenderer::AddBeliefs(const FirmwareBeliefs& beliefs) {
  const MazeDimensions dims = kernel_.world().maze_dimensions();
  auto centre = [&](Cell c) { return CellCentre(c, Heading::kNorth, dims); };
  // believed walls: a strip on top of each, so that true and believed walls are seen together
  for (const auto& [cell, w] : beliefs.walls) {
    for (int side = 0; side < 4; ++side) {
      const uint8_t bit = static_cast<uint8_t>(1 << side);  // north, east, south, west
      if (!(w.known & bit) || !(w.walls & bit)) continue;
      mjvGeom* g = NewGeom();
      if (g == nullptr) return;
      const bool north_south = side == 0 || side == 2;
      const double dx = side == 1 ? 0.5 : side == 3 ? -0.5 : 0;
      const double dy = side == 0 ? 0.5 : side == 2 ? -0.5 : 0;
      const mjtNum size[3] = {north_south ? dims.cell_m / 2 : 0.004,
                              north_south ? 0.004 : dims.cell_m / 2, 0.002};
      const Pose2D c = centre({cell.first, cell.second});
      const mjtNum pos[3] = {c.x_m + dims.cell_m * dx, c.y_m + dims.cell_m * dy,
                             dims.wall_height_m + 0.003};
      mjv_initGeom(g, mjGEOM_BOX, size, pos, nullptr, kBelievedWall);
      g->category = mjCAT_DECOR;
      g->emission = 0.5f;
    }
  }
  for (const Cell& c : beliefs.visited) {
    mjvGeom* g = NewGeom();
    if (g == nullptr) return;
    const mjtNum size[3] = {dims.cell_m / 6, dims.cell_m / 6, 0.0005};
    const Pose2D p = centre(c);
    const mjtNum pos[3] = {p.x_m, p.y_m, 0.001};
    mjv_initGeom(g, mjGEOM_BOX, size, pos, nullptr, kVisited);
    g->category = mjCAT_DECOR;
  }
  // cell colours: a tile over the floor inside the walls, under the visited marks
  for (const auto& [cell, letter] : beliefs.colours) {
    const std::optional<Rgb8> colour = CellColourOf(letter);
    if (!colour) continue;
    mjvGeom* g = NewGeom();
    if (g == nullptr) return;
    const double half_m = (dims.cell_m - dims.wall_thickness_m) / 2;
    const mjtNum size[3] = {half_m, half_m, 0.0004};
    const Pose2D p = centre({cell.first, cell.second});
    const mjtNum pos[3] = {p.x_m, p.y_m, 0.0005};
    const float rgba[4] = {colour->r / 255.0f, colour->g / 255.0f, colour->b / 255.0f, 1};
    mjv_initGeom(g, mjGEOM_BOX, size, pos, nullptr, rgba);
    g->category = mjCAT_DECOR;
  }
  // cell texts: MuJoCo's own labels, at the cell centre
  for (const auto& [cell, text] : beliefs.texts) {
    mjvGeom* g = NewGeom();
    if (g == nullptr) return;
    const Pose2D p = centre({cell.first, cell.second});
    const mjtNum pos[3] = {p.x_m, p.y_m, 0.002};
    mjv_initGeom(g, mjGEOM_LABEL, nullptr, pos, nullptr, nullptr);
    std::snprintf(g->label, sizeof(g->label), "%s", text.c_str());
    g->category = mjCAT_DECOR;
  }
  for (size_t i = 1; i < beliefs.path.size(); ++i) {
    mjvGeom* g = NewGeom();
    if (g == nullptr) return;
    mjv_initGeom(g, mjGEOM_CAPSULE, nullptr, nullptr, nullptr, kPlannedPath);
    const Pose2D pa = centre(beliefs.path[i - 1]), pb = centre(beliefs.path[i]);
    mjv_makeConnector(g, mjGEOM_CAPSULE, dims.cell_m / 30, pa.x_m, pa.y_m, 0.004, pb.x_m, pb.y_m,
                      0.004);
    g->category = mjCAT_DECOR;
    g->emission = 0.5f;
  }
}

void SceneRenderer::Draw(const mjrRect& viewport, const mjvCamera& camera,
                         const DrawOptions& options) {
  CopyState();
  mjvCamera cam = camera;
  mjv_updateScene(model_, data_, &option_, &perturb_, &cam, mjCAT_ALL, &scene_);
  const auto& chunks = kernel_.world().scenery_chunks();
  for (size_t i = 0; i < chunks.size(); ++i) {
    mjv_addGeoms(chunks[i].model.get(), scenery_data_[i], &option_, &perturb_, mjCAT_ALL, &scene_);
  }
  if (options.beams) AddBeams();
  if (options.beliefs && options.firmware != nullptr) AddBeliefs(*options.firmware);
  mjr_render(viewport, &scene_, &context_);

  std::string hud;
  for (const std::string& line : options.hud) hud += (hud.empty() ? "" : "\n") + line;
  if (!hud.empty())
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, hud.c_str(), nullptr, &context_);
  if (options.clock) {
    char clock[32];
    std::snprintf(clock, sizeof(clock), "%.3f s", data_->time);
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, viewport, "time", clock, &context_);
  }
}

Image SceneRenderer::Snapshot(int width, int height, const std::string& camera,
                              const DrawOptions& options) {
  if (width < 16 || height < 16 || width > kMaxWidth || height > kMaxHeight) {
    throw InputError("a picture is 16x16 to " + std::to_string(kMaxWidth) + "x" +
                     std::to_string(kMaxHeight) + " pixels, not " + std::to_string(width) + "x" +
                     std::to_string(height));
  }
  const mjvCamera cam = Camera(camera, static_cast<double>(width) / height);
  if (width > context_.offWidth || height > context_.offHeight) {
    MakeContext(std::max(width, context_.offWidth), std::max(height, context_.offHeight));
  }
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  const mjrRect viewport{0, 0, width, height};
  Draw(viewport, cam, options);
  return Read(viewport);
}

Image SceneRenderer::Read(const mjrRect& viewport) {
  const int width = viewport.width, height = viewport.height;
  Image image{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * height * 3)};
  std::vector<uint8_t> bottom_up(image.rgb.size());
  mjr_readPixels(bottom_up.data(), nullptr, viewport, &context_);
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(bottom_up.data() + row * static_cast<size_t>(height - 1 - y), row,
                image.rgb.data() + row * static_cast<size_t>(y));
  }
  return image;
}

void SceneRenderer::MoveCamera(int action, double dx, double dy, mjvCamera* camera) {
  mjv_moveCamera(model_, action, dx, dy, &scene_, camera);
}

}  // namespace unimouse
