// SPDX-License-Identifier: GPL-3.0-or-later
#include "page_data.h"

#include <cmath>

#include "robot_spec.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using nlohmann::json;

// the signals a student looks at first: what the motors get, what the encoders and sensors say
bool PlottedByDefault(const std::string& name) {
  for (const char* part : {"voltage_v", "current_a", "encoder_counts", "tof."}) {
    if (name.find(part) != std::string::npos && name != "battery.voltage_v") return true;
  }
  return false;
}

json Number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json RobotPath(const RecordedRobot& robot, bool ghost, const std::string& source,
               std::pair<double, double> footprint) {
  json t = json::array(), x = json::array(), y = json::array(), yaw = json::array();
  for (const Timed<Pose2D>& p : robot.poses) {
    t.push_back(p.t_s);
    x.push_back(Number(p.value.x_m));
    y.push_back(Number(p.value.y_m));
    yaw.push_back(Number(p.value.yaw_rad));
  }
  return {{"name", robot.name},
          {"ghost", ghost},
          {"source", source},
          {"length_m", footprint.first},
          {"width_m", footprint.second},
          {"t", t},
          {"x", x},
          {"y", y},
          {"yaw", yaw}};
}

json Cells(const std::vector<Cell>& cells) {
  json out = json::array();
  for (const Cell& c : cells) out.push_back({c.x, c.y});
  return out;
}

}  // namespace

std::pair<double, double> RobotFootprint(const std::string& robot_file_text) {
  std::pair<double, double> footprint{0.12, 0.10};
  try {
    const RobotSpec spec = ParseRobotSpec(robot_file_text, "robot file");
    double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
    bool any = false;
    for (const GeomSpec& g : spec.chassis.geoms) {
      if (g.type != "box") continue;
      min_x = std::min(min_x, g.pos_m[0] - g.size_m[0] / 2);
      max_x = std::max(max_x, g.pos_m[0] + g.size_m[0] / 2);
      min_y = std::min(min_y, g.pos_m[1] - g.size_m[1] / 2);
      max_y = std::max(max_y, g.pos_m[1] + g.size_m[1] / 2);
      any = true;
    }
    if (any) footprint = {max_x - min_x, max_y - min_y};
  } catch (const InputError&) {
    // a file this unimouse cannot read is drawn at a micromouse's size
  }
  return footprint;
}

json ReplayPageData(const Recording& recording, const std::vector<RecordedRobot>& ghosts,
                    const std::vector<std::string>& signals,
                    const std::optional<Divergence>& divergence) {
  json page;
  const auto run = recording.run_metadata;
  page["title"] = recording.path + (run.count("seed") ? ", seed " + run.at("seed") : "") +
                  (run.count("status") ? ", " + run.at("status") : "");
  page["end_s"] = recording.end_s;

  json scenery = json::array();
  for (const StaticBox& box : recording.scenery) {
    scenery.push_back({{"kind", box.kind == StaticBox::Kind::kWall   ? "wall"
                                : box.kind == StaticBox::Kind::kPost ? "post"
                                                                     : "obstacle"},
                       {"x", box.center_m[0]},
                       {"y", box.center_m[1]},
                       {"size_x", 2 * box.half_m[0]},
                       {"size_y", 2 * box.half_m[1]},
                       {"yaw", box.yaw_rad}});
  }
  page["scenery"] = scenery;
  page["cell_m"] = recording.maze ? json(recording.maze->cell_m) : json(nullptr);

  json robots = json::array();
  for (const RecordedRobot& robot : recording.robots) {
    const auto file = recording.attachments.find(robot.file);
    robots.push_back(
        RobotPath(robot, false, recording.path,
                  RobotFootprint(file == recording.attachments.end() ? "" : file->second)));
  }
  for (const RecordedRobot& ghost : ghosts) {
    robots.push_back(
        RobotPath(ghost, true, ghost.name,
                  robots[0].count("length_m")
                      ? std::pair<double, double>{robots[0]["length_m"], robots[0]["width_m"]}
                      : RobotFootprint("")));
  }
  page["robots"] = robots;

  // the plotted signals, thinned evenly to at most kMaxPlotSamples
  std::vector<size_t> columns;
  for (size_t i = 0; i < recording.signal_names.size(); ++i) {
    const std::string& name = recording.signal_names[i];
    const bool chosen = signals.empty()
                            ? PlottedByDefault(name)
                            : std::find(signals.begin(), signals.end(), name) != signals.end();
    if (chosen) columns.push_back(i);
  }
  for (const std::string& name : signals) {
    if (std::find(recording.signal_names.begin(), recording.signal_names.end(), name) ==
        recording.signal_names.end()) {
      throw InputError("--signal " + name + ": the recording has no such signal");
    }
  }
  const size_t rows = recording.signal_times_s.size();
  const size_t stride = std::max<size_t>(1, (rows + kMaxPlotSamples - 1) / kMaxPlotSamples);
  json times = json::array(), series = json::array();
  for (size_t r = 0; r < rows; r += stride) times.push_back(recording.signal_times_s[r]);
  for (size_t column : columns) {
    json values = json::array();
    for (size_t r = 0; r < rows; r += stride)
      values.push_back(Number(recording.signal_rows[r][column]));
    series.push_back({{"name", recording.signal_names[column]}, {"values", values}});
  }
  page["signals"] = {{"t", times}, {"series", series}};

  json events = json::array();
  for (const RecordedEvent& e : recording.events) {
    events.push_back({{"t", e.t_s}, {"kind", e.kind}, {"robot", e.robot}, {"text", e.text}});
  }
  page["events"] = events;
  json log = json::array();
  for (const RecordedLogLine& l : recording.log) {
    log.push_back({{"t", l.t_s}, {"level", l.level}, {"name", l.name}, {"message", l.message}});
  }
  page["log"] = log;

  json beliefs = json::array();
  for (const Timed<FirmwareBeliefs>& b : recording.beliefs) {
    json walls = json::array(), colours = json::array(), texts = json::array();
    for (const auto& [cell, w] : b.value.walls)
      walls.push_back({cell.first, cell.second, w.walls, w.known});
    for (const auto& [cell, letter] : b.value.colours) {
      if (const std::optional<Rgb8> rgb = CellColourOf(letter)) {
        colours.push_back({cell.first, cell.second, HexColour(*rgb)});
      }
    }
    for (const auto& [cell, text] : b.value.texts) texts.push_back({cell.first, cell.second, text});
    beliefs.push_back({{"t", b.t_s},
                       {"walls", walls},
                       {"visited", Cells(b.value.visited)},
                       {"path", Cells(b.value.path)},
                       {"colours", colours},
                       {"texts", texts}});
  }
  page["beliefs"] = beliefs;
  json hud = json::array();
  for (const auto& h : recording.hud) hud.push_back({{"t", h.t_s}, {"lines", h.value}});
  page["hud"] = hud;
  // the first robot's values (the one whose beliefs are drawn)
  json values = json::array();
  if (!recording.firmware_values.empty()) {
    for (const auto& v : recording.firmware_values.begin()->second) {
      json named = json::object();
      for (const auto& [name, value] : v.value) named[name] = Number(value);
      values.push_back({{"t", v.t_s}, {"values", named}});
    }
  }
  page["values"] = values;
  if (divergence) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the runs first diverge at %.3f s: the robots are %.1f cm apart there",
                  divergence->t_s, divergence->distance_m * 100);
    page["divergence"] = {
        {"t", divergence->t_s}, {"distance_m", divergence->distance_m}, {"text", text}};
  } else {
    page["divergence"] = nullptr;
  }
  return page;
}

}  // namespace unimouse
