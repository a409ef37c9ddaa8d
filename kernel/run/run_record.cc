// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_record.h"

#include <variant>

namespace unimouse {

namespace {

nlohmann::json FileOrNull(const std::optional<FileRecord>& file) {
  return file ? ToJson(*file) : nlohmann::json(nullptr);
}

nlohmann::json PoseJson(const Pose2D& pose) {
  return {{"x_m", pose.x_m}, {"y_m", pose.y_m}, {"yaw_rad", pose.yaw_rad}};
}

nlohmann::json DriverJson(const DriverRecord& driver) {
  nlohmann::json link = nullptr;
  if (driver.link) {
    link = {{"transport", driver.link->transport},
            {"spec", driver.link->spec},
            {"profile", driver.link->profile},
            {"firmware", FileOrNull(driver.link->firmware)}};
  }
  return {{"controller", FileOrNull(driver.controller)}, {"link", link}};
}

// a scenario's values with their Lua types
template <class Map>
nlohmann::json ValuesJson(const Map& values) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : values) {
    out[name] = std::visit([](const auto& v) { return nlohmann::json(v); }, value);
  }
  return out;
}

nlohmann::json ScenarioJson(const ScenarioRunRecord& s) {
  nlohmann::json records = nlohmann::json::object();
  for (const auto& [list, rows] : s.outcome.records) {
    for (const ScenarioRecord& row : rows) records[list].push_back(ValuesJson(row));
  }
  nlohmann::json out = {{"name", s.name},
                        {"file", s.file.file},
                        {"sha256", s.file.sha256},
                        {"params", ValuesJson(s.params)},
                        {"status", s.outcome.status},
                        {"reason", s.outcome.reason},
                        {"scores", ValuesJson(s.outcome.scores)},
                        {"records", records},
                        {"hud", s.hud}};
  if (!s.traceback.empty()) out["traceback"] = s.traceback;
  return out;
}

}  // namespace

nlohmann::json ContactJson(const Contact& c, const std::vector<std::string>& robot_names) {
  const auto name = [&](int robot) { return robot_names[static_cast<size_t>(robot)]; };
  nlohmann::json side = nullptr;
  if (c.side == 'P') side = "post";
  if (c.side != 0 && c.side != 'P') side = std::string(1, c.side);
  return {{"robot", name(c.robot)},
          {"t_s", c.time_s},
          {"with", c.other_robot >= 0 ? "robot" : "scenery"},
          {"other_robot", c.other_robot >= 0 ? nlohmann::json(name(c.other_robot)) : nullptr},
          {"x_m", c.x_m},
          {"y_m", c.y_m},
          {"cell", c.cell ? nlohmann::json{c.cell->x, c.cell->y} : nlohmann::json(nullptr)},
          {"side", side},
          {"part", c.part}};
}

nlohmann::json RunRecordJson(const RunRecord& record) {
  const RunRecord& r = record;
  nlohmann::json j = NewResultRecord("run");
  const RobotRecord& first = r.robot();
  j["robot"] = first.file.file;
  j["robot_name"] = r.robot_name;
  j["robot_sha256"] = first.file.sha256;
  j["driver"] = DriverJson(first.driver);
  SetMazeIdentity(j, r.maze);
  j["seed"] = r.seed;
  j["duration_s"] = r.duration_s;
  j["status"] = r.status;
  if (!r.error.empty()) j["error"] = r.error;
  j["sim_time_s"] = r.sim_time_s;
  j["steps"] = r.steps;
  j["wall_time_s"] = r.wall_time_s;
  j["real_time_factor"] = r.real_time_factor;
  j["wall_time_split_s"] = {{"physics", r.wall_time_split.physics_s},
                            {"components", r.wall_time_split.components_s},
                            {"firmware", r.wall_time_split.firmware_s},
                            {"scenario", r.wall_time_split.scenario_s}};
  j["firmware_paced"] = r.firmware_paced;
  j["robot_pose"] = PoseJson(first.pose);
  j["collision_proxy_overflows"] = r.collision_proxy_overflows;
  nlohmann::json robots = nlohmann::json::array();
  for (const RobotRecord& robot : r.robots) {
    robots.push_back({{"name", robot.name},
                      {"file", robot.file.file},
                      {"sha256", robot.file.sha256},
                      {"driver", DriverJson(robot.driver)},
                      {"pose", PoseJson(robot.pose)},
                      {"wall_contacts", robot.wall_contacts},
                      {"robot_contacts", robot.robot_contacts},
                      {"restarts", robot.restarts}});
  }
  j["robots"] = robots;
  if (r.scenario) j["scenario"] = ScenarioJson(*r.scenario);
  if (const auto& p = r.real_time_pacing) {
    j["real_time_pacing"] = {{"steps", p->steps},
                             {"lateness_p50_us", p->lateness_p50_us},
                             {"lateness_p99_us", p->lateness_p99_us},
                             {"lateness_max_us", p->lateness_max_us},
                             {"late_steps", p->late_steps},
                             {"fell_behind", p->fell_behind}};
  }
  if (r.pictures_written > 0) {
    j["pictures"] = {{"written", r.pictures_written}, {"renderer", r.pictures_renderer}};
  } else if (!r.pictures_unavailable.empty()) {
    j["pictures"] = {{"written", 0}, {"unavailable", r.pictures_unavailable}};
  }
  if (r.firmware_maze) j["firmware_maze"] = "maze.png";
  if (!r.measurements.empty()) j["measurements"] = r.measurements;
  if (r.restarts) j["restarts"] = *r.restarts;
  std::vector<std::string> names;
  for (const RobotRecord& robot : r.robots) names.push_back(robot.name);
  nlohmann::json contacts = nlohmann::json::array();
  for (const Contact& c : r.contacts) contacts.push_back(ContactJson(c, names));
  j["contacts"] = contacts;
  j["contacts_not_kept"] = r.contacts_not_kept;
  j["warnings"] = r.warnings;
  j["exit_code"] = r.exit_code;
  if (r.view) {
    j["view"] = {{"frames", r.view->frames}, {"frames_per_second", r.view->frames_per_second}};
  }
  return j;
}

}  // namespace unimouse
