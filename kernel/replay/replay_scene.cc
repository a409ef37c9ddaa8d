// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

// a ghost is seen through: a third of its colour
constexpr float kGhostAlpha = 0.35f;

}  // namespace

ReplayScene::ReplayScene(const Recording& recording, std::vector<RecordedRobot> ghosts,
                         const PluginRegistry& registry)
    : recording_(recording), ghosts_(std::move(ghosts)) {
  std::vector<KernelRobot> robots;
  for (const RecordedRobot& r : recording.robots) {
    const auto file = recording.attachments.find(r.file);
    if (r.file.empty() || file == recording.attachments.end()) {
      throw InputError(recording.path + ": the recording carries no robot file to draw " +
                       (r.name.empty() ? "its robot" : r.name) + " with");
    }
    KernelRobot robot{ParseRobotSpec(file->second, r.file), r.name, r.poses.front().value};
    robots.push_back(std::move(robot));
  }
  for (size_t i = 0; i < ghosts_.size(); ++i) {
    robots.push_back(
        {robots.front().spec, "ghost" + std::to_string(i + 1), ghosts_[i].poses.front().value});
  }
  // several robots need names of their own; the only robot keeps none
  if (robots.size() > 1) {
    for (size_t i = 0; i < robots.size(); ++i) {
      if (robots[i].name.empty()) robots[i].name = "robot" + std::to_string(i + 1);
    }
  }
  KernelOptions options;
  options.start_components = false;
  options.boxes = recording.scenery;
  options.output_dir = std::filesystem::temp_directory_path().string();
  options.log_sink = [](double, int, const std::string&, const std::string&) {};
  kernel_ = Kernel::Create(robots, nullptr, registry, options);

  // ghosts seen through
  mjModel& m = kernel_->world().mutable_model();
  for (int g = 0; g < m.ngeom; ++g) {
    const char* body = mj_id2name(&m, mjOBJ_BODY, m.geom_bodyid[g]);
    if (body != nullptr && std::string(body).rfind("ghost", 0) == 0)
      m.geom_rgba[4 * g + 3] *= kGhostAlpha;
  }

  // each signal of a recorded robot by its recorded name: with several robots, "name/signal"
  const std::vector<std::string>& names = kernel_->model().signal_names;
  for (const std::string& name : names) {
    int column = -1;
    for (size_t r = 0; r < recording.robots.size() && column < 0; ++r) {
      const std::string& prefix = kernel_->robot_prefix(static_cast<int>(r));
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string recorded =
          (recording.robots.size() > 1 ? recording.robots[r].name + "/" : std::string()) +
          name.substr(prefix.size());
      const auto at =
          std::find(recording.signal_names.begin(), recording.signal_names.end(), recorded);
      if (at != recording.signal_names.end())
        column = static_cast<int>(at - recording.signal_names.begin());
    }
    signal_column_.push_back(column);
  }

  for (const RecordedEvent& e : recording.events) marks_.push_back(e.t_s);
  for (const RecordedLogLine& l : recording.log) {
    if (l.level >= 2) marks_.push_back(l.t_s);
  }
  std::sort(marks_.begin(), marks_.end());
  marks_.erase(std::unique(marks_.begin(), marks_.end()), marks_.end());
  for (const Timed<Pose2D>& pose : recording.robots.front().poses)
    sample_times_.push_back(pose.t_s);
  ShowAt(0);
}

void ReplayScene::ShowAt(double t_s) {
  t_s = std::clamp(t_s, 0.0, recording_.end_s);
  time_s_ = t_s;
  mjData& d = kernel_->state().data();
  d.time = t_s;
  const size_t recorded = recording_.robots.size();
  for (size_t i = 0; i < recorded + ghosts_.size(); ++i) {
    const RecordedRobot& robot = i < recorded ? recording_.robots[i] : ghosts_[i - recorded];
    kernel_->world().PlaceRobot(d, PoseAt(robot, t_s), static_cast<int>(i));
  }
  std::vector<double>& signals = kernel_->state().signals();
  const auto& times = recording_.signal_times_s;
  signal_row_ = std::upper_bound(times.begin(), times.end(), t_s) - times.begin() - 1;
  const ptrdiff_t row = signal_row_;
  for (size_t i = 0; i < signal_column_.size() && i < signals.size(); ++i) {
    signals[i] = row >= 0 && signal_column_[i] >= 0 ? recording_.signal_rows[row][signal_column_[i]]
                                                    : std::nan("");
  }
  const int b = Recording::Latest(recording_.beliefs, t_s);
  beliefs_ = b >= 0 ? recording_.beliefs[b].value : FirmwareBeliefs{};
}

std::vector<std::string> ReplayScene::Hud(const std::vector<std::string>& signals) const {
  std::vector<std::string> lines;
  const int h = Recording::Latest(recording_.hud, time_s_);
  if (h >= 0) lines = recording_.hud[h].value;
  for (const auto& [robot, entries] : recording_.firmware_values) {
    const int v = Recording::Latest(entries, time_s_);
    if (v < 0) continue;
    std::string line = robot.empty() || recording_.robots.size() == 1 ? "firmware:" : robot + ":";
    for (const auto& [name, value] : entries[v].value) {
      char number[32];
      std::snprintf(number, sizeof(number), "%g", value);
      line += " " + name + "=" + number;
    }
    lines.push_back(line);
  }
  const ptrdiff_t row = signal_row_;
  for (const std::string& name : signals) {
    const auto& names = recording_.signal_names;
    const auto column = std::find(names.begin(), names.end(), name);
    if (column == names.end())
      throw InputError("--signal " + name + ": the recording has no such signal");
    char value[32] = "-";
    if (row >= 0)
      std::snprintf(value, sizeof(value), "%g",
                    recording_.signal_rows[row][column - names.begin()]);
    lines.push_back(name + " = " + value);
  }
  return lines;
}

}  // namespace unimouse
