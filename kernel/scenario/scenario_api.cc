// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario_api.h"

#include <lua5.4/lauxlib.h>
#include <lua5.4/lua.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <iterator>
#include <map>
#include <numbers>
#include <optional>
#include <string_view>

#include "install_paths.h"
#include "lua_patterns.h"
#include "rng.h"
#include "scenario.h"
#include "text_file.h"
#include "unimouse/errors.h"
#include "yaml_doc.h"

namespace unimouse {

namespace {
const TableArgument& KnownTableArgument(std::string_view name);
}  // namespace

// the C++ bodies behind `sim.*`; a struct so that they may reach Scenario's private parts. Each
// reads its arguments through LuaCall and reports a bad one by throwing (see lua_call.h).
struct ScenarioApi {
  static Scenario& Self(const LuaCall& call) { return Scenario::Of(call.state()); }
  static Kernel& RunningKernel(const LuaCall& call) {
    Scenario& s = Self(call);
    if (s.kernel_ == nullptr) {
      call.Fail(std::string(call.name()) + " works only in run, once the world exists");
    }
    return *s.kernel_;
  }
  static void NotInRun(const LuaCall& call) {
    if (Self(call).kernel_ != nullptr) {
      call.Fail(std::string(call.name()) + " works only in world, before the run");
    }
  }

  static int ScenarioTable(LuaCall& call) {
    call.CheckTable(1);
    if (call.FieldType(1, "name") != LUA_TSTRING) call.Fail("sim.scenario needs a name");
    if (call.FieldType(1, "run") != LUA_TFUNCTION) call.Fail("sim.scenario needs a run function");
    const int finish = call.FieldType(1, "finish");
    if (finish != LUA_TNIL && finish != LUA_TFUNCTION)
      call.Fail("sim.scenario: finish is a function");
    lua_settop(call.state(), 1);
    return 1;
  }

  static int Time(LuaCall& call) {
    const Scenario& s = Self(call);
    lua_pushnumber(call.state(), s.kernel_ ? s.kernel_->state().data().time : 0.0);
    return 1;
  }

  // the robot named by argument `arg` (sim.robots() gives the names), or without one the robot
  // of the controller that calls, else the first
  static int RobotIndex(const LuaCall& call, int arg) {
    const Scenario& s = Self(call);
    if (lua_isnoneornil(call.state(), arg)) return s.current_robot_;
    const std::string name = call.CheckString(arg);
    for (size_t i = 0; i < s.robot_names_.size(); ++i) {
      if (s.robot_names_[i] == name) return static_cast<int>(i);
    }
    std::string names;
    for (const std::string& n : s.robot_names_) names += (names.empty() ? "" : ", ") + n;
    call.Fail("no robot named '" + name + "' (the run has: " + names + ")");
  }

  static int Robots(LuaCall& call) {
    const Scenario& s = Self(call);
    lua_State* L = call.state();
    lua_createtable(L, static_cast<int>(s.robot_names_.size()), 0);
    for (size_t i = 0; i < s.robot_names_.size(); ++i) {
      lua_pushstring(L, s.robot_names_[i].c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    return 1;
  }

  static int RobotTouchingRobot(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    const int other = k.contacts().touching_robot(RobotIndex(call, 1));
    if (other < 0) {
      lua_pushnil(call.state());
    } else {
      lua_pushstring(call.state(), Self(call).robot_names_[static_cast<size_t>(other)].c_str());
    }
    return 1;
  }

  static int RobotGetPose(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    const Pose2D p = k.world().RobotPose(k.state().data(), RobotIndex(call, 1));
    lua_State* L = call.state();
    lua_createtable(L, 0, 3);
    lua_pushnumber(L, p.x_m);
    lua_setfield(L, -2, "x_m");
    lua_pushnumber(L, p.y_m);
    lua_setfield(L, -2, "y_m");
    lua_pushnumber(L, p.yaw_rad);
    lua_setfield(L, -2, "yaw_rad");
    return 1;
  }

  static int RobotGetVelocity(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    const mjData& d = k.state().data();
    const int robot = RobotIndex(call, 1);
    const Pose2D p = k.world().RobotPose(d, robot);
    const int dof = k.mj_model().body_dofadr[k.world().robot_body(robot)];
    // free joint: linear velocity in world axes, angular in the body's; the body is level
    lua_State* L = call.state();
    lua_createtable(L, 0, 2);
    lua_pushnumber(L, d.qvel[dof] * std::cos(p.yaw_rad) + d.qvel[dof + 1] * std::sin(p.yaw_rad));
    lua_setfield(L, -2, "v_m_per_s");
    lua_pushnumber(L, d.qvel[dof + 5]);
    lua_setfield(L, -2, "omega_rad_per_s");
    return 1;
  }

  static int RobotGetCell(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    const Pose2D p = k.world().RobotPose(k.state().data(), RobotIndex(call, 1));
    const Cell cell = CellAt(p.x_m, p.y_m, k.world().maze_dimensions());
    lua_State* L = call.state();
    lua_createtable(L, 0, 2);
    lua_pushinteger(L, cell.x);
    lua_setfield(L, -2, "x");
    lua_pushinteger(L, cell.y);
    lua_setfield(L, -2, "y");
    return 1;
  }

  static int RobotIsTouchingWall(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    lua_pushboolean(call.state(), k.contacts().touching_wall(RobotIndex(call, 1)));
    return 1;
  }

  static int MazeIsGoal(LuaCall& call) {
    const Scenario& s = Self(call);
    const Cell c{static_cast<int>(call.CheckInteger(1)), static_cast<int>(call.CheckInteger(2))};
    bool goal = false;
    if (s.maze_goals_) {
      for (const Cell& g : *s.maze_goals_) goal = goal || g == c;
    }
    lua_pushboolean(call.state(), goal);
    return 1;
  }

  static int MazeGetStart(LuaCall& call) {
    const Scenario& s = Self(call);
    lua_State* L = call.state();
    lua_createtable(L, 0, 2);
    lua_pushinteger(L, s.maze_start_.x);
    lua_setfield(L, -2, "x");
    lua_pushinteger(L, s.maze_start_.y);
    lua_setfield(L, -2, "y");
    return 1;
  }

  static int MazeGetDimensions(LuaCall& call) {
    const Scenario& s = Self(call);
    // in run the world holds the maze, in world the scenario does
    const Maze* maze = s.kernel_ ? s.kernel_->world().maze() : s.world_.maze.get();
    if (maze == nullptr) call.Fail("sim.maze_get_dimensions: no maze loaded");
    const MazeDimensions& d = maze->dimensions();
    lua_State* L = call.state();
    lua_createtable(L, 0, 6);
    lua_pushinteger(L, maze->width());
    lua_setfield(L, -2, "width");
    lua_pushinteger(L, maze->height());
    lua_setfield(L, -2, "height");
    lua_pushnumber(L, d.cell_m);
    lua_setfield(L, -2, "cell_m");
    lua_pushnumber(L, d.wall_thickness_m);
    lua_setfield(L, -2, "wall_thickness_m");
    lua_pushnumber(L, d.wall_height_m);
    lua_setfield(L, -2, "wall_height_m");
    lua_pushstring(L, MazeClassName(maze->maze_class()));
    lua_setfield(L, -2, "class");
    return 1;
  }

  static int RobotPlace(LuaCall& call) {
    call.CheckTable(1);
    const Pose2D pose{call.NumberField(1, "x_m"), call.NumberField(1, "y_m"),
                      call.NumberField(1, "yaw_deg", 90) * std::numbers::pi / 180};
    lua_getfield(call.state(), 1, "robot");
    const int robot = RobotIndex(call, lua_gettop(call.state()));
    lua_pop(call.state(), 1);
    Scenario& s = Self(call);
    if (s.kernel_ == nullptr) {
      if (robot == 0) {
        s.world_.spawn = pose;
      } else {
        s.world_.robot_spawns[robot] = pose;
      }
    } else {
      s.kernel_->world().PlaceRobot(s.kernel_->state().data(), pose, robot);
    }
    return 0;
  }

  static int RobotReset(LuaCall& call) {
    Scenario& s = Self(call);
    if (s.kernel_ == nullptr) call.Fail("sim.robot_reset: only in run");
    const int robot = RobotIndex(call, 1);
    s.kernel_->world().PlaceRobot(s.kernel_->state().data(), s.kernel_->world().spawn(robot),
                                  robot);
    return 0;
  }

  // a signal by its name; a controller's names are its robot's first ("left_motor.voltage" is
  // "b/left_motor.voltage" for robot b's controller), else the name as given
  static int SignalIndex(const LuaCall& call, const Kernel& k) {
    const std::string name = call.CheckString(1);
    const Scenario& s = Self(call);
    if (k.robot_count() > 1) {
      const int own = k.model().FindSignal(k.robot_prefix(s.current_robot_) + name);
      if (own >= 0) return own;
    }
    const int id = k.model().FindSignal(name);
    if (id < 0) call.Fail("no signal named '" + name + "'");
    return id;
  }
  static int SignalGet(LuaCall& call) {
    const Kernel& k = RunningKernel(call);
    lua_pushnumber(call.state(), k.state().signals()[SignalIndex(call, k)]);
    return 1;
  }
  static int SignalSet(LuaCall& call) {
    Kernel& k = RunningKernel(call);
    const int id = SignalIndex(call, k);
    const double v = call.CheckNumber(2);
    if (!std::isfinite(v)) call.Fail("a signal must be finite");
    k.state().signals()[id] = v;
    return 0;
  }

  static int WallAdd(LuaCall& call) {
    NotInRun(call);
    call.CheckTable(1);
    const double x1 = call.NumberField(1, "x1_m"), y1 = call.NumberField(1, "y1_m");
    const double x2 = call.NumberField(1, "x2_m"), y2 = call.NumberField(1, "y2_m");
    const double thickness = call.NumberField(1, "thickness_m", 0.012);
    const double height = call.NumberField(1, "height_m", 0.05);
    const double length = std::hypot(x2 - x1, y2 - y1);
    if (length <= 0 || thickness <= 0 || height <= 0) {
      call.Fail("a wall needs a length, thickness and height");
    }
    Self(call).world_.boxes.push_back({StaticBox::Kind::kWall,
                                       {(x1 + x2) / 2, (y1 + y2) / 2, height / 2},
                                       {length / 2, thickness / 2, height / 2},
                                       std::atan2(y2 - y1, x2 - x1)});
    return 0;
  }

  static int BoxAdd(LuaCall& call) {
    NotInRun(call);
    call.CheckTable(1);
    lua_State* L = call.state();
    if (call.FieldType(1, "size_m") != LUA_TTABLE) {
      call.Fail("sim.box_add: field 'size_m' must be a table {x, y, z}");
    }
    lua_pushliteral(L, "size_m");
    lua_rawget(L, 1);
    double size[3];
    for (int i = 0; i < 3; ++i) {
      lua_rawgeti(L, -1, i + 1);
      size[i] = lua_tonumber(L, -1);
      lua_pop(L, 1);
      if (!(size[i] > 0) || !std::isfinite(size[i])) {
        call.Fail("sim.box_add: size_m needs three sizes greater than 0");
      }
    }
    lua_pop(L, 1);
    Self(call).world_.boxes.push_back(
        {StaticBox::Kind::kObstacle,
         {call.NumberField(1, "x_m"), call.NumberField(1, "y_m"), size[2] / 2},
         {size[0] / 2, size[1] / 2, size[2] / 2},
         call.NumberField(1, "yaw_deg", 0) * std::numbers::pi / 180});
    return 0;
  }

  static int MazeLoad(LuaCall& call) {
    NotInRun(call);
    const std::string name = call.CheckString(1);
    // the contest's dimensions: "auto" follows DefaultMazeClass, a 16 x 16 maze may be either
    std::string maze_class = "auto";
    if (!call.IsNoneOrNil(2)) {
      call.CheckTable(2);
      maze_class = call.StringField(2, "class", maze_class);
      if (maze_class != "auto" && maze_class != "classic" && maze_class != "half") {
        call.Fail("sim.maze_load: class is auto, classic or half, not '" + maze_class + "'");
      }
    }
    // a maze that cannot be read throws InputError, which the boundary raises as the message
    Scenario& s = Self(call);
    try {
      s.world_.maze_file = ResolveDataFile(name, "mazes/", ".txt");
      s.world_.maze = std::make_unique<Maze>(LoadMaze(s.world_.maze_file));
      if (maze_class != "auto") {
        s.world_.maze->set_class(maze_class == "half" ? MazeClass::kHalfSize : MazeClass::kClassic);
      }
    } catch (const InputError& e) {
      // named on the command line (--set, --maze): the user's input, not the script, is wrong
      for (const auto& [param, value] : s.overrides_) {
        if (value == name) {
          s.bad_input_ =
              "parameter " + param + " = " + value + " (from the command line): " + e.what();
        }
      }
      throw;
    }
    s.maze_goals_ = std::make_unique<std::vector<Cell>>(s.world_.maze->goals());
    s.maze_start_ = s.world_.maze->start();
    return 0;
  }

  static int HudSet(LuaCall& call) {
    const lua_Integer line = call.CheckInteger(1);
    if (line < 1 || line > 16) call.Fail("hud lines are 1 to 16");
    std::string text = call.CheckString(2);
    std::vector<std::string>& hud = Self(call).hud_;
    if (hud.size() < static_cast<size_t>(line)) hud.resize(static_cast<size_t>(line));
    hud[static_cast<size_t>(line - 1)] = std::move(text);
    return 0;
  }

  static int SnapshotSave(LuaCall& call) {
    const std::string file = call.CheckString(1);
    std::string camera = "top";
    lua_Integer width = 640, height = 480;
    if (!call.IsNoneOrNil(2)) {
      call.CheckTable(2);
      camera = call.StringField(2, "camera", camera);
      width = call.IntegerField(2, "width", width);
      height = call.IntegerField(2, "height", height);
    }
    // pictures stay inside the run's output directory
    if (file.empty() || file[0] == '/' || file.find("..") != std::string::npos || file.size() < 5 ||
        file.substr(file.size() - 4) != ".png") {
      call.Fail("sim.snapshot_save: '" + file +
                "' is not a relative name ending in .png inside the run's output directory");
    }
    Scenario& s = Self(call);
    const std::string why =
        s.picture_taker_
            ? s.picture_taker_(file, camera, static_cast<int>(width), static_cast<int>(height))
            : std::string("this run takes no pictures");
    lua_State* L = call.state();
    lua_pushboolean(L, why.empty());
    if (why.empty()) return 1;
    lua_pushstring(L, why.c_str());
    return 2;
  }

  // text appended to a file of the run's output directory: a log the firmware printed, as CSV
  static int FileAppend(LuaCall& call) {
    const std::string file = call.CheckString(1);
    const std::string text = call.CheckString(2);
    const auto ends_with = [&](std::string_view end) {
      return file.size() > end.size() &&
             file.compare(file.size() - end.size(), end.size(), end) == 0;
    };
    if (file.find('/') != std::string::npos || file.find("..") != std::string::npos ||
        file[0] == '.' || !(ends_with(".csv") || ends_with(".txt"))) {
      call.Fail("sim.file_append: '" + file +
                "' is not a plain file name ending in .csv or .txt (files stay in the run's "
                "output directory)");
    }
    Scenario& s = Self(call);
    lua_State* L = call.state();
    const auto refuse = [&](const std::string& why) {
      lua_pushboolean(L, 0);
      lua_pushstring(L, why.c_str());
      return 2;
    };
    if (s.output_dir_.empty()) return refuse("this run writes no files");
    if (s.file_bytes_ + text.size() > kMaxScenarioFile_bytes) {
      return refuse("a scenario writes at most " + std::to_string(kMaxScenarioFile_bytes) +
                    " bytes of files in a run");
    }
    auto it = s.files_.find(file);
    if (it == s.files_.end()) {
      if (s.files_.size() >= kMaxScenarioFiles) {
        return refuse("a scenario writes at most " + std::to_string(kMaxScenarioFiles) +
                      " files in a run");
      }
      // a fresh file for each run: never lines of an earlier one
      auto out = std::make_unique<std::ofstream>(s.output_dir_ + "/" + file,
                                                 std::ios::binary | std::ios::trunc);
      if (!*out) return refuse("cannot write " + file);
      it = s.files_.emplace(file, std::move(out)).first;
    }
    *it->second << text;
    it->second->flush();
    s.file_bytes_ += text.size();
    if (!*it->second) return refuse("cannot write " + file);
    lua_pushboolean(L, 1);
    return 1;
  }

  // a moment of the run for its recording's /events, and a line of its log as print writes one.
  // The kind is a word, so that a player or a test can pick events by it; "contact" and "lost"
  // stay the run's own. A bound, so that a script in a loop cannot flood the recording.
  static int Event(LuaCall& call) {
    Kernel& k = RunningKernel(call);
    const std::string kind = call.CheckString(1);
    const bool word = !kind.empty() && kind.size() <= kMaxScenarioEventKind_bytes &&
                      std::all_of(kind.begin(), kind.end(), [](char c) {
                        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                      });
    if (!word) {
      call.Fail("sim.event: kind '" + kind.substr(0, 64) +
                "' is not a word of lowercase letters, digits and _ (at most " +
                std::to_string(kMaxScenarioEventKind_bytes) + ")");
    }
    if (kind == "contact" || kind == "lost") {
      call.Fail("sim.event: kind '" + kind + "' is the run's own; give another");
    }
    const std::string_view text = call.CheckText(2);
    Scenario& s = Self(call);
    std::string robot;
    if (!call.IsNoneOrNil(3)) robot = s.robot_names_[static_cast<size_t>(RobotIndex(call, 3))];
    if (s.events_kept_ == kMaxScenarioEvents) {
      if (s.events_not_kept_++ == 0) {
        k.Log(UNIMOUSE_LOG_WARNING, "scenario",
              "sim.event: more than " + std::to_string(kMaxScenarioEvents) +
                  " events in a run: later ones are counted, not recorded");
      }
      return 0;
    }
    ++s.events_kept_;
    // cut as the log cuts a message, copying no more of a long text than is kept
    std::string kept(text.substr(0, kMaxScenarioEventText_bytes));
    if (text.size() > kMaxScenarioEventText_bytes) {
      kept += "... (" + std::to_string(text.size()) + " bytes in all)";
    }
    const ScenarioEvent event{k.state().data().time, kind, std::move(robot), std::move(kept)};
    k.Log(UNIMOUSE_LOG_INFO, "scenario", event.text);
    if (s.event_sink_) s.event_sink_(event);
    return 0;
  }

  static int Decide(const LuaCall& call, const char* status) {
    Scenario& s = Self(call);
    if (s.finished()) return 0;
    s.outcome_.status = status;
    s.outcome_.reason = call.OptString(1, "");
    if (s.kernel_)
      s.kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", std::string(status) + ": " + s.outcome_.reason);
    return 0;
  }
  static int Pass(LuaCall& call) { return Decide(call, "passed"); }
  static int Fail(LuaCall& call) { return Decide(call, "failed"); }

  // a score keeps its Lua type: an integer (a count) is an integer in the result
  static int ScoreSet(LuaCall& call) {
    const std::string name = call.CheckString(1);
    const double number = call.CheckNumber(2);
    if (!std::isfinite(number)) call.Fail("sim.score_set: score '" + name + "' is not finite");
    auto& scores = Self(call).outcome_.scores;
    if (!scores.contains(name) && scores.size() >= kMaxScenarioScores) {
      call.Fail("sim.score_set: more than " + std::to_string(kMaxScenarioScores) +
                " scores in a run (docs/limits.md)");
    }
    lua_State* L = call.state();
    scores[name] =
        lua_isinteger(L, 2) ? ScenarioValue(int64_t{lua_tointeger(L, 2)}) : ScenarioValue(number);
    return 0;
  }

  // a row of a table the result holds: fields of a list keep their types from row to row
  static int RecordAdd(LuaCall& call) {
    const std::string list = call.CheckString(1);
    call.CheckTable(2);
    Scenario& s = Self(call);
    CheckRecordName(call, "list", list);
    if (s.record_count_ >= kMaxScenarioRecords) {
      call.Fail("sim.record_add: more than " + std::to_string(kMaxScenarioRecords) +
                " records in a run (docs/limits.md)");
    }
    lua_State* L = call.state();
    ScenarioRecord record;
    std::map<std::string, int>& types = s.record_fields_[list];
    std::map<std::string, int> field_types;
    lua_settop(L, 2);
    lua_pushnil(L);
    while (lua_next(L, 2) != 0) {
      if (lua_type(L, -2) != LUA_TSTRING) {
        call.Fail(std::string("sim.record_add: a field name is a string, not a ") +
                  lua_typename(L, lua_type(L, -2)));
      }
      if (record.size() == kMaxScenarioRecordFields) {
        call.Fail("sim.record_add: a record has at most " +
                  std::to_string(kMaxScenarioRecordFields) + " fields");
      }
      const std::string field = lua_tostring(L, -2);
      CheckRecordName(call, "field", field);
      std::optional<ScenarioValue> value = ScalarAt(L, -1);
      const int type = lua_type(L, -1);
      if (!value) {
        call.Fail("sim.record_add: field '" + field + "' is a " + lua_typename(L, type) +
                  "; a field is a number, a boolean or a string");
      }
      if (type == LUA_TNUMBER && !std::isfinite(lua_tonumber(L, -1))) {
        call.Fail("sim.record_add: field '" + field + "' is not finite");
      }
      if (type == LUA_TSTRING && lua_rawlen(L, -1) > kMaxScenarioRecordText_bytes) {
        call.Fail("sim.record_add: field '" + field + "' is longer than " +
                  std::to_string(kMaxScenarioRecordText_bytes) + " bytes");
      }
      const auto known = types.find(field);
      if (known != types.end() && known->second != type) {
        call.Fail("sim.record_add: field '" + field + "' of list '" + list + "' is a " +
                  lua_typename(L, known->second) + " in earlier records, not a " +
                  lua_typename(L, type));
      }
      record.emplace(field, std::move(*value));
      field_types.emplace(field, type);
      lua_pop(L, 1);
    }
    // only a record that is added sets its fields' types
    for (const auto& [field, type] : field_types) types.emplace(field, type);
    s.outcome_.records[list].push_back(std::move(record));
    ++s.record_count_;
    return 0;
  }

  // list and field names are words, so that a table or a CSV file can use them as they are
  static void CheckRecordName(const LuaCall& call, const char* what, const std::string& name) {
    const bool word =
        !name.empty() && name.size() <= 64 && !std::isdigit(static_cast<unsigned char>(name[0])) &&
        std::all_of(name.begin(), name.end(),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!word) {
      call.Fail(std::string("sim.record_add: ") + what + " name '" + name.substr(0, 64) +
                "' is not a word of letters, digits and _ (at most 64, not starting with a digit)");
    }
  }

  // the sandbox's print: to the run's log, each value as tostring gives it
  static int Print(LuaCall& call) {
    std::string line;
    for (int i = 1; i <= call.count(); ++i) line += (i > 1 ? "\t" : "") + call.ToText(i);
    const Scenario& s = Self(call);
    if (s.kernel_) {
      s.kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", line);
    } else {
      std::fprintf(stderr, "scenario: %s\n", line.c_str());
    }
    return 0;
  }

  // the firmware's log lines since the last call, as {text, time_s}; for the event dispatcher
  static int TakeFirmwareLines(LuaCall& call) {
    std::vector<std::pair<double, std::string>>& lines = Self(call).firmware_lines_;
    lua_State* L = call.state();
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

  // the firmware's restarts since the last call, as {time_s, count}; for the event dispatcher
  static int TakeFirmwareRestarts(LuaCall& call) {
    Scenario& s = Self(call);
    std::vector<Scenario::Restart>& restarts = s.firmware_restarts_;
    lua_State* L = call.state();
    lua_createtable(L, static_cast<int>(restarts.size()), 0);
    for (size_t i = 0; i < restarts.size(); ++i) {
      lua_createtable(L, 0, 3);
      lua_pushnumber(L, restarts[i].time_s);
      lua_setfield(L, -2, "time_s");
      lua_pushinteger(L, restarts[i].count);
      lua_setfield(L, -2, "count");
      const auto robot = static_cast<size_t>(restarts[i].robot);
      lua_pushstring(L, robot < s.robot_names_.size() ? s.robot_names_[robot].c_str() : "");
      lua_setfield(L, -2, "robot");
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    restarts.clear();
    return 1;
  }

  // math.random, drawing from the run's seed
  static int Random(LuaCall& call) {
    const double u = Self(call).rng_.Uniform();
    lua_State* L = call.state();
    if (call.count() == 0) {
      lua_pushnumber(L, u);
      return 1;
    }
    lua_Integer lo = 1, hi = call.CheckInteger(1);
    if (call.count() >= 2) {
      lo = hi;
      hi = call.CheckInteger(2);
    }
    if (lo > hi) call.Fail("math.random: interval is empty");
    // unsigned, so that the whole range of integers fits: hi - lo + 1 would overflow
    const lua_Unsigned span = static_cast<lua_Unsigned>(hi) - static_cast<lua_Unsigned>(lo);
    const auto offset =
        std::min(static_cast<lua_Unsigned>(u * (static_cast<double>(span) + 1.0)), span);
    lua_pushinteger(L, static_cast<lua_Integer>(static_cast<lua_Unsigned>(lo) + offset));
    return 1;
  }

  // string.find, string.match and the search under the prelude's string.gmatch and
  // string.gsub: Lua's patterns, each step counted against the instruction budget
  static std::function<void(int64_t)> Charger(const LuaCall& call) {
    lua_State* L = call.state();
    return [L](int64_t steps) { Scenario::Of(L).Spend(L, 1, steps); };
  }
  // a start position as Lua reads one (negative from the end, 0 as 1), 0-based; may be past
  // the end
  static size_t StartAt(const LuaCall& call, int arg, size_t length) {
    const lua_Integer init = call.IsNoneOrNil(arg) ? 1 : call.CheckInteger(arg);
    if (init > 0) return static_cast<size_t>(init) - 1;
    if (init == 0 || init < -static_cast<lua_Integer>(length)) return 0;
    return length - static_cast<size_t>(-init);
  }
  // pushes the captures, or the whole match when there are none and `whole` says so
  static int PushCaptures(const LuaCall& call, std::string_view subject, const PatternMatch& m,
                          bool whole) {
    lua_State* L = call.state();
    size_t bytes = whole && m.captures.empty() ? m.end - m.start : 0;
    for (const PatternCapture& c : m.captures) bytes += c.length;
    // the captures are the script's memory: a clean memory error rather than a limit passed
    const LuaMemory* memory = LuaMemory::Of(L);
    if (memory != nullptr && memory->in_use_bytes() + bytes > memory->limit_bytes()) {
      throw ScriptError("not enough memory", /*located=*/true);
    }
    if (whole && m.captures.empty()) {
      lua_pushlstring(L, subject.data() + m.start, m.end - m.start);
      return 1;
    }
    for (const PatternCapture& c : m.captures) {
      if (c.position) {
        lua_pushinteger(L, static_cast<lua_Integer>(c.start) + 1);
      } else {
        lua_pushlstring(L, subject.data() + c.start, c.length);
      }
    }
    return static_cast<int>(m.captures.size());
  }
  static int FindOrMatch(const LuaCall& call, bool find) {
    const std::string_view subject = call.CheckText(1), pattern = call.CheckText(2);
    const size_t from = StartAt(call, 3, subject.size());
    lua_State* L = call.state();
    if (from > subject.size()) {
      lua_pushnil(L);
      return 1;
    }
    if (find && (lua_toboolean(L, 4) || PatternMatcher::IsPlain(pattern))) {
      const auto at = PatternMatcher::FindPlain(subject, pattern, from, Charger(call));
      if (!at) {
        lua_pushnil(L);
        return 1;
      }
      lua_pushinteger(L, static_cast<lua_Integer>(*at) + 1);
      lua_pushinteger(L, static_cast<lua_Integer>(*at + pattern.size()));
      return 2;
    }
    const bool anchored = !pattern.empty() && pattern[0] == '^';
    PatternMatcher matcher(subject, pattern.substr(anchored ? 1 : 0), Charger(call));
    const std::optional<PatternMatch> m = matcher.Find(from, anchored);
    if (!m) {
      lua_pushnil(L);
      return 1;
    }
    if (!find) return PushCaptures(call, subject, *m, /*whole=*/true);
    lua_pushinteger(L, static_cast<lua_Integer>(m->start) + 1);
    lua_pushinteger(L, static_cast<lua_Integer>(m->end));
    return 2 + PushCaptures(call, subject, *m, /*whole=*/false);
  }
  static int StringFind(LuaCall& call) { return FindOrMatch(call, true); }
  static int StringMatch(LuaCall& call) { return FindOrMatch(call, false); }
  // search(s, pattern, from, anchored, skip_empty_at) -> start, end, captures... or nil:
  // positions 1-based, `from` already within 1..#s+1, no '^' in the pattern (anchored says it)
  static int PatternSearch(LuaCall& call) {
    const std::string_view subject = call.CheckText(1), pattern = call.CheckText(2);
    const lua_Integer from = call.CheckInteger(3), skip = call.CheckInteger(5);
    lua_State* L = call.state();
    if (from < 1 || static_cast<size_t>(from) > subject.size() + 1) {
      lua_pushnil(L);
      return 1;
    }
    PatternMatcher matcher(subject, pattern, Charger(call));
    const std::optional<PatternMatch> m =
        matcher.Find(static_cast<size_t>(from) - 1, lua_toboolean(L, 4) != 0,
                     skip > 0 ? static_cast<size_t>(skip) - 1 : std::string_view::npos);
    if (!m) {
      lua_pushnil(L);
      return 1;
    }
    lua_pushinteger(L, static_cast<lua_Integer>(m->start) + 1);
    lua_pushinteger(L, static_cast<lua_Integer>(m->end));
    return 2 + PushCaptures(call, subject, *m, /*whole=*/false);
  }

  // the instruction budget's error once it is spent, else nil: the prelude's protected calls
  // pass it on
  static int BudgetSpent(LuaCall& call) {
    const std::string& spent = Self(call).Spent(call.state(), 1);
    if (spent.empty()) {
      lua_pushnil(call.state());
    } else {
      lua_pushstring(call.state(), spent.c_str());
    }
    return 1;
  }

  // check_keys(name, ...): the arguments of sim.<name>, whose table argument may hold only the
  // keys its signature names; a misspelt optional key would otherwise be a default silently used
  static int CheckKeys(LuaCall& call) {
    const std::string name = call.CheckString(1);
    const TableArgument& table = KnownTableArgument(name);
    const int arg = table.position + 1;
    lua_State* L = call.state();
    if (table.position == 0 || lua_type(L, arg) != LUA_TTABLE) return 0;
    // the first unknown key in sorted order, so that the message does not depend on hashing
    std::string unknown;
    bool found = false;
    int64_t keys = 0;
    lua_pushnil(L);
    while (lua_next(L, arg) != 0) {
      lua_pop(L, 1);
      ++keys;
      const int type = lua_type(L, -1);
      const std::string key = type == LUA_TSTRING || type == LUA_TNUMBER
                                  ? ErrorText(L, -1)
                                  : std::string("of type ") + luaL_typename(L, -1);
      const bool known = type == LUA_TSTRING &&
                         std::find(table.keys.begin(), table.keys.end(), key) != table.keys.end();
      if (!known && (!found || key < unknown)) {
        unknown = key;
        found = true;
      }
    }
    // going through the keys is work the instruction count does not see
    Scenario& s = Self(call);
    s.Spend(L, 1, keys);
    if (!found) return 0;
    const std::string near = NearestWord(unknown, table.keys);
    std::string known;
    for (const std::string& k : table.keys) known += (known.empty() ? "" : ", ") + k;
    s.unknown_key_ = "unknown key " + unknown + " in sim." + name +
                     (near.empty() ? " (its keys: " + known + ")" : ", did you mean " + near + "?");
    // a tail call (`return sim.scenario {...}`) leaves no frame to read the caller's line from:
    // the line is then the one the key is written on
    if (ScriptLine(L, 1).empty()) {
      const int line = LineOfKey(s.file_, unknown);
      if (line > 0) {
        throw ScriptError(s.file_ + ":" + std::to_string(line) + ": " + s.unknown_key_,
                          /*located=*/true);
      }
    }
    call.Fail(s.unknown_key_);
  }

  // the first line of `file` where `key =` is written, or 0
  static int LineOfKey(const std::string& file, const std::string& key) {
    const auto word = [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    const std::string text = ReadTextFile(file);
    int line = 1;
    for (size_t at = 0; at < text.size(); ++at) {
      if (text[at] == '\n') ++line;
      if (text.compare(at, key.size(), key) != 0 || (at > 0 && word(text[at - 1]))) continue;
      size_t next = at + key.size();
      if (next < text.size() && word(text[next])) continue;
      while (next < text.size() && (text[next] == ' ' || text[next] == '\t')) ++next;
      if (next < text.size() && text[next] == '=' &&
          (next + 1 == text.size() || text[next + 1] != '=')) {
        return line;
      }
    }
    return 0;
  }

  // work the prelude's wrappers leave to C (table.move's elements), counted as instructions
  static int Charge(LuaCall& call) {
    const double work = call.CheckNumber(1);
    const double most = kScenarioInstructionBudget + 1.0;  // beyond it, any amount is spent
    Self(call).Spend(call.state(), 1, static_cast<int64_t>(work > 0 ? std::min(work, most) : 0));
    return 0;
  }
};

namespace {

// the list of the scenario API: every function with the API level it appeared in, its
// signature and what it does. Removing one or changing a signature breaks scenarios: the golden
// test (tests/golden/scenario_api.txt) makes that a deliberate change. Verbs: get, set, add,
// place, load, is, save; nouns: robot, maze, signal, hud, score, record, wall, box, snapshot.
constexpr ApiEntry kApi[] = {
    {"scenario", ScenarioApi::ScenarioTable, 1,
     "scenario{name, params?, world?, run, finish?, robots?} -> table",
     "declares the scenario a file returns"},
    {"time", ScenarioApi::Time, 1, "time() -> seconds", "sim time"},
    {"next_tick", nullptr, 1, "next_tick()", "waits one physics step"},
    {"wait", nullptr, 1, "wait(seconds)", "waits sim time"},
    {"wait_until", nullptr, 1, "wait_until(condition, {timeout_s?}) -> boolean",
     "waits until condition() is true; false on timeout"},
    {"robots", ScenarioApi::Robots, 4, "robots() -> {name, ...}",
     "the run's robots, in the order of the command line; the one-robot functions take a name "
     "as their last argument (robot_place{robot = name})"},
    {"robot_touching_robot", ScenarioApi::RobotTouchingRobot, 4,
     "robot_touching_robot(name?) -> name or nil", "the other robot this one touches now"},
    {"robot_get_pose", ScenarioApi::RobotGetPose, 1, "robot_get_pose(name?) -> {x_m, y_m, yaw_rad}",
     "where the robot is"},
    {"robot_get_velocity", ScenarioApi::RobotGetVelocity, 1,
     "robot_get_velocity(name?) -> {v_m_per_s, omega_rad_per_s}",
     "forward speed and yaw rate, counter-clockwise positive"},
    {"robot_get_cell", ScenarioApi::RobotGetCell, 1, "robot_get_cell(name?) -> {x, y}",
     "the maze cell under the robot's centre"},
    {"robot_is_touching_wall", ScenarioApi::RobotIsTouchingWall, 1,
     "robot_is_touching_wall(name?) -> boolean",
     "whether the robot touches a wall, post or obstacle"},
    {"robot_place", ScenarioApi::RobotPlace, 1, "robot_place{x_m, y_m, yaw_deg?, robot?}",
     "puts the robot there at rest; in world, its start"},
    {"robot_reset", ScenarioApi::RobotReset, 1, "robot_reset(name?)",
     "puts the robot back at its start, at rest (run)"},
    {"maze_load", ScenarioApi::MazeLoad, 1, "maze_load(name_or_file, {class?})",
     "builds a maze (world) at its contest's dimensions; class auto, classic or half"},
    {"maze_get_dimensions", ScenarioApi::MazeGetDimensions, 3,
     "maze_get_dimensions() -> {width, height, cell_m, wall_thickness_m, wall_height_m, class}",
     "the loaded maze's size in cells and its dimensions in metres"},
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
    {"event", ScenarioApi::Event, 5, "event(kind, text, robot?)",
     "marks a moment of the run (a run starts, the goal, a penalty) on the recording's /events "
     "and in the log; kind a word of a-z, 0-9 and _"},
    {"snapshot_save", ScenarioApi::SnapshotSave, 2,
     "snapshot_save(file, {camera?, width?, height?}) -> ok, reason?",
     "a PNG of the scene now, in the run's output directory; cameras top, chase, free"},
    {"file_append", ScenarioApi::FileAppend, 4, "file_append(file, text) -> ok, reason?",
     "appends text to a .csv or .txt file in the run's output directory (a plain name)"},
    {"score_set", ScenarioApi::ScoreSet, 1, "score_set(name, value)",
     "a number for the result; an integer stays an integer"},
    {"record_add", ScenarioApi::RecordAdd, 3, "record_add(list, {field = value, ...})",
     "a row of the list `list` in the result (each run of a contest); fields are numbers, "
     "booleans or strings, each keeping its type from row to row"},
    {"on", nullptr, 1, "on(kind, handler)",
     "calls handler(event) on cell_entered {x, y}, wall_contact, gate_crossed {name, direction}, "
     "firmware_log {text}, firmware_restart {count}"},
    {"gate_add", nullptr, 1, "gate_add{name, x1_m, y1_m, x2_m, y2_m}",
     "a line whose crossings raise gate_crossed, direction +1 from its right to its left"},
    {"pass", ScenarioApi::Pass, 1, "pass(reason?)", "ends the challenge: passed"},
    {"fail", ScenarioApi::Fail, 1, "fail(reason?)", "ends the challenge: failed"},
};

// the host's functions, for the prelude; internal, so outside the API levels (since 0)
constexpr ApiEntry kHost[] = {
    {"print", ScenarioApi::Print, 0, "print(...)", "to the run's log, with the sim time"},
    {"random", ScenarioApi::Random, 0, "random(m?, n?) -> number",
     "math.random, from the run's seed"},
    {"take_firmware_lines", ScenarioApi::TakeFirmwareLines, 0,
     "take_firmware_lines() -> {{text, time_s}, ...}", "the firmware's log lines since last time"},
    {"take_firmware_restarts", ScenarioApi::TakeFirmwareRestarts, 0,
     "take_firmware_restarts() -> {{time_s, count, robot}, ...}",
     "the firmware's restarts since last time"},
    {"budget_spent", ScenarioApi::BudgetSpent, 0, "budget_spent() -> message?",
     "the instruction budget's error once it is spent"},
    {"charge", ScenarioApi::Charge, 0, "charge(instructions)",
     "counts work done in C against the instruction budget"},
    {"check_keys", ScenarioApi::CheckKeys, 0, "check_keys(name, ...)",
     "refuses a key the table argument of sim.<name> does not take"},
    {"string.find", ScenarioApi::StringFind, 0, "string.find(s, pattern, init?, plain?)",
     "string.find with its work counted"},
    {"string.match", ScenarioApi::StringMatch, 0, "string.match(s, pattern, init?)",
     "string.match with its work counted"},
    {"pattern_search", ScenarioApi::PatternSearch, 0,
     "pattern_search(s, pattern, from, anchored, skip_empty_at) -> start, end, captures...",
     "the next match, its work counted, for string.gmatch and string.gsub"},
};

// `text` split at its commas outside braces, each part without its surrounding spaces
std::vector<std::string_view> SplitArguments(std::string_view text) {
  std::vector<std::string_view> parts;
  int depth = 0;
  size_t from = 0;
  for (size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && (text[i] == '{' || text[i] == '(')) ++depth;
    if (i < text.size() && (text[i] == '}' || text[i] == ')')) --depth;
    if (i == text.size() || (text[i] == ',' && depth == 0)) {
      std::string_view part = text.substr(from, i - from);
      part.remove_prefix(std::min(part.size(), part.find_first_not_of(' ')));
      part = part.substr(0, part.find_last_not_of(' ') + 1);
      if (!part.empty()) parts.push_back(part);
      from = i + 1;
    }
  }
  return parts;
}

// the table argument of the function called `name`, worked out once
const TableArgument& KnownTableArgument(std::string_view name) {
  static const std::vector<std::pair<std::string_view, TableArgument>> tables = [] {
    std::vector<std::pair<std::string_view, TableArgument>> all;
    for (const ApiEntry& e : kApi) all.emplace_back(e.name, TableArgumentOf(e));
    return all;
  }();
  static const TableArgument kNone;
  for (const auto& [n, table] : tables) {
    if (n == name) return table;
  }
  return kNone;
}

}  // namespace

TableArgument TableArgumentOf(const ApiEntry& entry) {
  std::string_view call = entry.signature;
  call = call.substr(0, call.find(" ->"));
  const size_t open = call.find_first_of("({");
  if (open == std::string_view::npos) return {};
  // "name{...}" takes one table; "name(a, {...})" lists its arguments between parentheses
  const std::vector<std::string_view> arguments =
      call[open] == '{' ? std::vector<std::string_view>{call.substr(open)}
                        : SplitArguments(call.substr(open + 1, call.size() - open - 2));
  TableArgument table;
  for (size_t i = 0; i < arguments.size(); ++i) {
    if (arguments[i].front() != '{') continue;
    const std::vector<std::string_view> keys =
        SplitArguments(arguments[i].substr(1, arguments[i].size() - 2));
    // "{field = value, ...}" takes keys of the scenario's choosing (sim.record_add's fields)
    if (std::find(keys.begin(), keys.end(), "...") != keys.end()) continue;
    table.position = static_cast<int>(i) + 1;
    for (std::string_view key : keys)
      table.keys.emplace_back(key.substr(0, key.find_first_of(" =?")));
  }
  return table;
}

std::span<const ApiEntry> ScenarioApiEntries() { return kApi; }

std::span<const ApiEntry> ScenarioHostEntries() { return kHost; }

std::optional<ScenarioValue> ScalarAt(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TBOOLEAN:
      return ScenarioValue(lua_toboolean(L, index) != 0);
    case LUA_TNUMBER:
      if (lua_isinteger(L, index)) return ScenarioValue(int64_t{lua_tointeger(L, index)});
      return ScenarioValue(double{lua_tonumber(L, index)});
    case LUA_TSTRING: {
      size_t length = 0;
      const char* text = lua_tolstring(L, index, &length);
      return ScenarioValue(std::string(text, length));
    }
    default:
      return std::nullopt;
  }
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
