// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario_api.h"

#include <lua5.4/lauxlib.h>
#include <lua5.4/lua.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <numbers>

#include "install_paths.h"
#include "rng.h"
#include "scenario.h"
#include "unimouse/errors.h"

namespace unimouse {

// the C functions behind `sim.*`; a struct so that they may reach Scenario's private parts
struct ScenarioApi {
  static Scenario& Self(lua_State* L) {
    lua_getfield(L, LUA_REGISTRYINDEX, "unimouse.scenario");
    auto* s = static_cast<Scenario*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    return *s;
  }
  static Kernel& RunningKernel(lua_State* L, const char* function) {
    Scenario& s = Self(L);
    if (s.kernel_ == nullptr)
      luaL_error(L, "%s works only in run, once the world exists", function);
    return *s.kernel_;
  }
  static double Field(lua_State* L, int table, const char* key, double fallback, bool required) {
    lua_getfield(L, table, key);
    if (lua_isnil(L, -1)) {
      lua_pop(L, 1);
      if (required) luaL_error(L, "missing field '%s'", key);
      return fallback;
    }
    if (!lua_isnumber(L, -1)) luaL_error(L, "field '%s' must be a number", key);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!std::isfinite(v)) luaL_error(L, "field '%s' must be finite", key);
    return v;
  }
  static void NotInRun(lua_State* L, const char* function) {
    if (Self(L).kernel_ != nullptr)
      luaL_error(L, "%s works only in world, before the run", function);
  }

  static int ScenarioTable(lua_State* L) {
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_getfield(L, 1, "name");
    if (!lua_isstring(L, -1)) luaL_error(L, "sim.scenario needs a name");
    lua_getfield(L, 1, "run");
    if (!lua_isfunction(L, -1)) luaL_error(L, "sim.scenario needs a run function");
    lua_getfield(L, 1, "finish");
    if (!lua_isnil(L, -1) && !lua_isfunction(L, -1))
      luaL_error(L, "sim.scenario: finish is a function");
    lua_settop(L, 1);
    return 1;
  }

  static int Time(lua_State* L) {
    Scenario& s = Self(L);
    lua_pushnumber(L, s.kernel_ ? s.kernel_->state().data().time : 0.0);
    return 1;
  }

  static int RobotGetPose(lua_State* L) {
    const Kernel& k = RunningKernel(L, "sim.robot_get_pose");
    const Pose2D p = k.world().RobotPose(k.state().data());
    lua_createtable(L, 0, 3);
    lua_pushnumber(L, p.x_m);
    lua_setfield(L, -2, "x_m");
    lua_pushnumber(L, p.y_m);
    lua_setfield(L, -2, "y_m");
    lua_pushnumber(L, p.yaw_rad);
    lua_setfield(L, -2, "yaw_rad");
    return 1;
  }

  static int RobotGetVelocity(lua_State* L) {
    const Kernel& k = RunningKernel(L, "sim.robot_get_velocity");
    const mjData& d = k.state().data();
    const Pose2D p = k.world().RobotPose(d);
    const int dof = k.mj_model().body_dofadr[k.world().robot_body()];
    // free joint: linear velocity in world axes, angular in the body's; the body is level
    lua_createtable(L, 0, 2);
    lua_pushnumber(L, d.qvel[dof] * std::cos(p.yaw_rad) + d.qvel[dof + 1] * std::sin(p.yaw_rad));
    lua_setfield(L, -2, "v_m_per_s");
    lua_pushnumber(L, d.qvel[dof + 5]);
    lua_setfield(L, -2, "omega_rad_per_s");
    return 1;
  }

  static int RobotGetCell(lua_State* L) {
    const Kernel& k = RunningKernel(L, "sim.robot_get_cell");
    const Pose2D p = k.world().RobotPose(k.state().data());
    const MazeDimensions dims;
    lua_createtable(L, 0, 2);
    lua_pushinteger(L, static_cast<lua_Integer>(std::floor(p.x_m / dims.cell_m)));
    lua_setfield(L, -2, "x");
    lua_pushinteger(L, static_cast<lua_Integer>(std::floor(p.y_m / dims.cell_m)));
    lua_setfield(L, -2, "y");
    return 1;
  }

  static int RobotIsTouchingWall(lua_State* L) {
    const Kernel& k = RunningKernel(L, "sim.robot_is_touching_wall");
    lua_pushboolean(L, k.world().RobotTouchesScenery(k.state().data()));
    return 1;
  }

  static int MazeIsGoal(lua_State* L) {
    Scenario& s = Self(L);
    const Cell c{static_cast<int>(luaL_checkinteger(L, 1)),
                 static_cast<int>(luaL_checkinteger(L, 2))};
    bool goal = false;
    if (s.maze_goals_) {
      for (const Cell& g : *s.maze_goals_) goal = goal || g == c;
    }
    lua_pushboolean(L, goal);
    return 1;
  }

  static int MazeGetStart(lua_State* L) {
    Scenario& s = Self(L);
    lua_createtable(L, 0, 2);
    lua_pushinteger(L, s.maze_start_.x);
    lua_setfield(L, -2, "x");
    lua_pushinteger(L, s.maze_start_.y);
    lua_setfield(L, -2, "y");
    return 1;
  }

  static int RobotPlace(lua_State* L) {
    luaL_checktype(L, 1, LUA_TTABLE);
    const Pose2D pose{Field(L, 1, "x_m", 0, true), Field(L, 1, "y_m", 0, true),
                      Field(L, 1, "yaw_deg", 90, false) * std::numbers::pi / 180};
    Scenario& s = Self(L);
    if (s.kernel_ == nullptr) {
      s.world_.spawn = pose;
    } else {
      s.kernel_->world().PlaceRobot(s.kernel_->state().data(), pose);
    }
    return 0;
  }

  static int RobotReset(lua_State* L) {
    Scenario& s = Self(L);
    if (s.kernel_ == nullptr) return luaL_error(L, "sim.robot_reset: only in run");
    s.kernel_->world().PlaceRobot(s.kernel_->state().data(), s.kernel_->world().spawn());
    return 0;
  }

  static int SignalIndex(lua_State* L, const Kernel& k) {
    const char* name = luaL_checkstring(L, 1);
    const int id = k.model().FindSignal(name);
    if (id < 0) luaL_error(L, "no signal named '%s'", name);
    return id;
  }
  static int SignalGet(lua_State* L) {
    const Kernel& k = RunningKernel(L, "sim.signal_get");
    lua_pushnumber(L, k.state().signals()[SignalIndex(L, k)]);
    return 1;
  }
  static int SignalSet(lua_State* L) {
    Kernel& k = RunningKernel(L, "sim.signal_set");
    const int id = SignalIndex(L, k);
    const double v = luaL_checknumber(L, 2);
    if (!std::isfinite(v)) luaL_error(L, "a signal must be finite");
    k.state().signals()[id] = v;
    return 0;
  }

  static int WallAdd(lua_State* L) {
    NotInRun(L, "sim.wall_add");
    luaL_checktype(L, 1, LUA_TTABLE);
    const double x1 = Field(L, 1, "x1_m", 0, true), y1 = Field(L, 1, "y1_m", 0, true);
    const double x2 = Field(L, 1, "x2_m", 0, true), y2 = Field(L, 1, "y2_m", 0, true);
    const double thickness = Field(L, 1, "thickness_m", 0.012, false);
    const double height = Field(L, 1, "height_m", 0.05, false);
    const double length = std::hypot(x2 - x1, y2 - y1);
    if (length <= 0 || thickness <= 0 || height <= 0)
      luaL_error(L, "a wall needs a length, thickness and height");
    Self(L).world_.boxes.push_back({StaticBox::Kind::kWall,
                                    {(x1 + x2) / 2, (y1 + y2) / 2, height / 2},
                                    {length / 2, thickness / 2, height / 2},
                                    std::atan2(y2 - y1, x2 - x1)});
    return 0;
  }

  static int BoxAdd(lua_State* L) {
    NotInRun(L, "sim.box_add");
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_getfield(L, 1, "size_m");
    luaL_checktype(L, -1, LUA_TTABLE);
    double size[3];
    for (int i = 0; i < 3; ++i) {
      lua_geti(L, -1, i + 1);
      size[i] = lua_tonumber(L, -1);
      if (!(size[i] > 0)) luaL_error(L, "size_m needs three sizes greater than 0");
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    Self(L).world_.boxes.push_back(
        {StaticBox::Kind::kObstacle,
         {Field(L, 1, "x_m", 0, true), Field(L, 1, "y_m", 0, true), size[2] / 2},
         {size[0] / 2, size[1] / 2, size[2] / 2},
         Field(L, 1, "yaw_deg", 0, false) * std::numbers::pi / 180});
    return 0;
  }

  static int MazeLoad(lua_State* L) {
    NotInRun(L, "sim.maze_load");
    const char* name = luaL_checkstring(L, 1);
    try {
      Scenario& s = Self(L);
      s.world_.maze = std::make_unique<Maze>(LoadMaze(ResolveDataFile(name, "mazes/", ".txt")));
      s.maze_goals_ = std::make_unique<std::vector<Cell>>(s.world_.maze->goals());
      s.maze_start_ = s.world_.maze->start();
    } catch (const InputError& e) {
      return luaL_error(L, "%s", e.what());
    }
    return 0;
  }

  static int HudSet(lua_State* L) {
    const lua_Integer line = luaL_checkinteger(L, 1);
    if (line < 1 || line > 16) luaL_error(L, "hud lines are 1 to 16");
    std::vector<std::string>& hud = Self(L).hud_;
    if (hud.size() < static_cast<size_t>(line)) hud.resize(static_cast<size_t>(line));
    hud[static_cast<size_t>(line - 1)] = luaL_checkstring(L, 2);
    return 0;
  }

  static int SnapshotSave(lua_State* L) {
    const std::string file = luaL_checkstring(L, 1);
    std::string camera = "top";
    lua_Integer width = 640, height = 480;
    if (!lua_isnoneornil(L, 2)) {
      luaL_checktype(L, 2, LUA_TTABLE);
      if (lua_getfield(L, 2, "camera") != LUA_TNIL) camera = luaL_checkstring(L, -1);
      if (lua_getfield(L, 2, "width") != LUA_TNIL) width = luaL_checkinteger(L, -1);
      if (lua_getfield(L, 2, "height") != LUA_TNIL) height = luaL_checkinteger(L, -1);
      lua_pop(L, 3);
    }
    // pictures stay inside the run's output directory
    if (file.empty() || file[0] == '/' || file.find("..") != std::string::npos || file.size() < 5 ||
        file.substr(file.size() - 4) != ".png") {
      return luaL_error(L,
                        "sim.snapshot_save: '%s' is not a relative name ending in .png inside "
                        "the run's output directory",
                        file.c_str());
    }
    Scenario& s = Self(L);
    const std::string why =
        s.picture_taker_
            ? s.picture_taker_(file, camera, static_cast<int>(width), static_cast<int>(height))
            : std::string("this run takes no pictures");
    lua_pushboolean(L, why.empty());
    if (why.empty()) return 1;
    lua_pushstring(L, why.c_str());
    return 2;
  }

  static int Decide(lua_State* L, const char* status) {
    Scenario& s = Self(L);
    if (s.finished()) return 0;
    s.outcome_.status = status;
    s.outcome_.reason = luaL_optstring(L, 1, "");
    if (s.kernel_)
      s.kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", std::string(status) + ": " + s.outcome_.reason);
    return 0;
  }
  static int Pass(lua_State* L) { return Decide(L, "passed"); }
  static int Fail(lua_State* L) { return Decide(L, "failed"); }

  static int ScoreSet(lua_State* L) {
    const char* name = luaL_checkstring(L, 1);
    Self(L).outcome_.scores[name] = luaL_checknumber(L, 2);
    return 0;
  }

  static int Print(lua_State* L) {
    std::string line;
    for (int i = 1; i <= lua_gettop(L); ++i) {
      line += (i > 1 ? "\t" : "") + std::string(luaL_tolstring(L, i, nullptr));
      lua_pop(L, 1);
    }
    Scenario& s = Self(L);
    if (s.kernel_) {
      s.kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", line);
    } else {
      std::fprintf(stderr, "scenario: %s\n", line.c_str());
    }
    return 0;
  }

  // the firmware's log lines since the last call, as {text, time_s}; for the event dispatcher
  static int TakeFirmwareLines(lua_State* L) {
    std::vector<std::pair<double, std::string>>& lines = Self(L).firmware_lines_;
    lua_createtable(L, static_cast<int>(lines.size()), 0);
    for (size_t i = 0; i < lines.size(); ++i) {
      lua_createtable(L, 0, 2);
      lua_pushstring(L, lines[i].second.c_str());
      lua_setfield(L, -2, "text");
      lua_pushnumber(L, lines[i].first);
      lua_setfield(L, -2, "time_s");
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lines.clear();
    return 1;
  }

  static int Random(lua_State* L) {
    lua_getfield(L, LUA_REGISTRYINDEX, "unimouse.rng");
    auto* rng = static_cast<RngStream*>(lua_touserdata(L, -1));
    lua_pop(L, 1);
    const double u = rng->Uniform();
    if (lua_gettop(L) == 0) {
      lua_pushnumber(L, u);
      return 1;
    }
    lua_Integer lo = 1, hi = luaL_checkinteger(L, 1);
    if (lua_gettop(L) >= 2) {
      lo = hi;
      hi = luaL_checkinteger(L, 2);
    }
    if (lo > hi) luaL_error(L, "math.random: interval is empty");
    lua_pushinteger(L, lo + static_cast<lua_Integer>(u * static_cast<double>(hi - lo + 1)));
    return 1;
  }
};

namespace {

// the list of the scenario API: every function with the API level it appeared in, its
// signature and what it does. Removing one or changing a signature breaks scenarios: the golden
// test (tests/golden/scenario_api.txt) makes that a deliberate change. Verbs: get, set, add,
// place, load, is, save; nouns: robot, maze, signal, hud, score, wall, box, snapshot.
constexpr ApiEntry kApi[] = {
    {"scenario", ScenarioApi::ScenarioTable, 1,
     "scenario{name, params?, world?, run, finish?} -> table",
     "declares the scenario a file returns"},
    {"time", ScenarioApi::Time, 1, "time() -> seconds", "sim time"},
    {"next_tick", nullptr, 1, "next_tick()", "waits one physics step"},
    {"wait", nullptr, 1, "wait(seconds)", "waits sim time"},
    {"wait_until", nullptr, 1, "wait_until(condition, {timeout_s?}) -> boolean",
     "waits until condition() is true; false on timeout"},
    {"robot_get_pose", ScenarioApi::RobotGetPose, 1, "robot_get_pose() -> {x_m, y_m, yaw_rad}",
     "where the robot is"},
    {"robot_get_velocity", ScenarioApi::RobotGetVelocity, 1,
     "robot_get_velocity() -> {v_m_per_s, omega_rad_per_s}",
     "forward speed and yaw rate, counter-clockwise positive"},
    {"robot_get_cell", ScenarioApi::RobotGetCell, 1, "robot_get_cell() -> {x, y}",
     "the maze cell under the robot's centre"},
    {"robot_is_touching_wall", ScenarioApi::RobotIsTouchingWall, 1,
     "robot_is_touching_wall() -> boolean", "whether the robot touches a wall, post or obstacle"},
    {"robot_place", ScenarioApi::RobotPlace, 1, "robot_place{x_m, y_m, yaw_deg?}",
     "puts the robot there at rest; in world, its start"},
    {"robot_reset", ScenarioApi::RobotReset, 1, "robot_reset()",
     "puts the robot back at its start, at rest (run)"},
    {"maze_load", ScenarioApi::MazeLoad, 1, "maze_load(name_or_file)", "builds a maze (world)"},
    {"maze_is_goal", ScenarioApi::MazeIsGoal, 1, "maze_is_goal(x, y) -> boolean",
     "whether a cell is a goal cell of the loaded maze"},
    {"maze_get_start", ScenarioApi::MazeGetStart, 1, "maze_get_start() -> {x, y}",
     "the loaded maze's start cell"},
    {"wall_add", ScenarioApi::WallAdd, 1,
     "wall_add{x1_m, y1_m, x2_m, y2_m, thickness_m?, height_m?}", "a straight wall (world)"},
    {"wall_arc", nullptr, 1,
     "wall_arc{cx_m, cy_m, radius_m, from_deg, to_deg, segments?, thickness_m?, height_m?}",
     "an arc of straight walls, counter-clockwise from from_deg to to_deg (world)"},
    {"wall_polyline", nullptr, 1,
     "wall_polyline{points = {{x_m, y_m}, ...}, thickness_m?, height_m?}",
     "straight walls joining the points in turn (world)"},
    {"box_add", ScenarioApi::BoxAdd, 1, "box_add{x_m, y_m, size_m = {x, y, z}, yaw_deg?}",
     "a box standing on the floor (world)"},
    {"signal_get", ScenarioApi::SignalGet, 1, "signal_get(name) -> number",
     "a robot signal: a sensor reading, a command"},
    {"signal_set", ScenarioApi::SignalSet, 1, "signal_set(name, value)",
     "writes a robot signal: drives the robot, injects a fault"},
    {"hud_set", ScenarioApi::HudSet, 1, "hud_set(line, text)", "a line of on-screen text, 1-16"},
    {"snapshot_save", ScenarioApi::SnapshotSave, 2,
     "snapshot_save(file, {camera?, width?, height?}) -> ok, reason?",
     "a PNG of the scene now, in the run's output directory; cameras top, chase, free"},
    {"score_set", ScenarioApi::ScoreSet, 1, "score_set(name, value)", "a number for the result"},
    {"on", nullptr, 1, "on(kind, handler)",
     "calls handler(event) on cell_entered {x, y}, wall_contact, gate_crossed {name, direction}, "
     "firmware_log {text}"},
    {"gate_add", nullptr, 1, "gate_add{name, x1_m, y1_m, x2_m, y2_m}",
     "a line whose crossings raise gate_crossed, direction +1 from its right to its left"},
    {"pass", ScenarioApi::Pass, 1, "pass(reason?)", "ends the challenge: passed"},
    {"fail", ScenarioApi::Fail, 1, "fail(reason?)", "ends the challenge: failed"},
};

}  // namespace

std::span<const ApiEntry> ScenarioApiEntries() { return kApi; }

SandboxFunctions ScenarioSandboxFunctions() {
  return {ScenarioApi::Random, ScenarioApi::Print, ScenarioApi::TakeFirmwareLines};
}

std::string DescribeScenarioApi() {
  std::string out = "scenario API level " + std::to_string(kScenarioApiLevel) + "\n";
  for (const ApiEntry& e : kApi) {
    out += "sim." + std::string(e.signature) + "  -- " + e.summary + " [since " +
           std::to_string(e.since) + "]\n";
  }
  return out;
}

}  // namespace unimouse
