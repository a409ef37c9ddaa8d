// SPDX-License-Identifier: GPL-3.0-or-later
#include "imported_run.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "replay.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) {
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(0, 1);
    cells.push_back(cell);
  }
  return cells;
}

const BodySpec* BodyWithJoint(const BodySpec& body, const std::string& joint) {
  if (body.joint && body.joint->name == joint) return &body;
  for (const BodySpec& child : body.bodies) {
    if (const BodySpec* found = BodyWithJoint(child, joint)) return found;
  }
  return nullptr;
}

// a wheel's radius: its largest round geom
double WheelRadius(const BodySpec& wheel) {
  double radius = 0;
  for (const GeomSpec& g : wheel.geoms) radius = std::max(radius, g.radius_m);
  return radius;
}

}  // namespace

RecordedRobot ReadImportedRun(const std::string& path, const RobotSpec* robot, Pose2D start) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the logged run");
  RecordedRobot run;
  run.name = std::filesystem::path(path).filename().string();
  std::map<std::string, size_t> column;
  bool pose_log = false;
  // an encoder log: the wheels' geometry, and the totals of the row before
  double counts_per_rad[2] = {0, 0}, radius[2] = {0, 0}, track = 0, last_counts[2] = {0, 0};
  Pose2D pose = start;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsv(line);
    if (column.empty()) {
      for (size_t i = 0; i < cells.size(); ++i) column[cells[i]] = i;
      pose_log = column.count("x_m") != 0;
      const std::vector<std::string> needed =
          pose_log ? std::vector<std::string>{"time_s", "x_m", "y_m", "yaw_rad"}
                   : std::vector<std::string>{"time_s", "left_counts", "right_counts"};
      for (const std::string& name : needed) {
        if (column.count(name) == 0) {
          throw InputError(where + "no column " + name +
                           " (a logged run has time_s,x_m,y_m,yaw_rad"
                           " or time_s,left_counts,right_counts)");
        }
      }
      if (!pose_log) {
        if (robot == nullptr) throw InputError(where + "an encoder log needs the robot's file");
        const fit::RobotWiring wiring = fit::WireRobot(*robot);
        const BodySpec* left = BodyWithJoint(robot->chassis, wiring.left.joint);
        const BodySpec* right = BodyWithJoint(robot->chassis, wiring.right.joint);
        if (left == nullptr || right == nullptr) {
          throw InputError(robot->file + ": no wheel body on the encoders' joints");
        }
        counts_per_rad[0] = wiring.left.counts_per_rad;
        counts_per_rad[1] = wiring.right.counts_per_rad;
        radius[0] = WheelRadius(*left);
        radius[1] = WheelRadius(*right);
        track = std::abs(left->pos_m[1] - right->pos_m[1]);
      }
      continue;
    }
    auto value = [&](const std::string& name) {
      const size_t i = column.at(name);
      if (i >= cells.size()) throw InputError(where + "no value in column " + name);
      char* end = nullptr;
      const double v = std::strtod(cells[i].c_str(), &end);
      if (cells[i].empty() || *end != '\0' || !std::isfinite(v)) {
        throw InputError(where + name + " '" + cells[i] + "' is not a finite number");
      }
      return v;
    };
    const double t = value("time_s");
    if (!run.poses.empty() && t < run.poses.back().t_s) {
      throw InputError(where + "time_s goes backwards (" + cells[column["time_s"]] + " after " +
                       std::to_string(run.poses.back().t_s) + ")");
    }
    if (pose_log) {
      run.poses.push_back({t, {value("x_m"), value("y_m"), value("yaw_rad")}});
      continue;
    }
    const double counts[2] = {value("left_counts"), value("right_counts")};
    if (!run.poses.empty()) {
      // each wheel's distance since the row before; the robot turns by their difference over the
      // track and moves by their mean along the heading halfway through the turn
      const double left = (counts[0] - last_counts[0]) / counts_per_rad[0] * radius[0];
      const double right = (counts[1] - last_counts[1]) / counts_per_rad[1] * radius[1];
      const double turn = (right - left) / track;
      pose.x_m += (left + right) / 2 * std::cos(pose.yaw_rad + turn / 2);
      pose.y_m += (left + right) / 2 * std::sin(pose.yaw_rad + turn / 2);
      pose.yaw_rad = std::remainder(pose.yaw_rad + turn, 2 * M_PI);
    }
    last_counts[0] = counts[0];
    last_counts[1] = counts[1];
    run.poses.push_back({t, pose});
  }
  if (run.poses.size() < 2) {
    throw InputError(path + ": a logged run needs a header and at least two rows");
  }
  return run;
}

}  // namespace unimouse
