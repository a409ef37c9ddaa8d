// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario.h"

#include <lua5.4/lauxlib.h>
#include <lua5.4/lua.h>
#include <lua5.4/lualib.h>

#include <cmath>
#include <cstring>

#include "lua_call.h"
#include "prelude.h"
#include "scenario_api.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {

namespace {

constexpr int kHookEvery = 1000;

// first line of a Lua error, which starts with file:line
std::string Headline(const std::string& message) { return message.substr(0, message.find('\n')); }

// keeps field `key` of a plain table in the registry: its reference, or LUA_REFNIL for nil
int RefField(lua_State* L, int table, const char* key) {
  lua_getfield(L, table, key);
  return luaL_ref(L, LUA_REGISTRYINDEX);
}

// what a script that ran out of allocations is told
std::string AllocationsSpent() {
  return "allocation budget exhausted: more than " +
         std::to_string(kScenarioAllocationBytes >> 20) +
         " MiB allocated between two waits (strings built in a loop?)";
}

}  // namespace

Scenario& Scenario::Of(lua_State* L) { return **static_cast<Scenario**>(lua_getextraspace(L)); }

Scenario::~Scenario() {
  if (L_ == nullptr) return;
  // a script's __gc may still call the API while the state closes: no kernel, no pictures then
  kernel_ = nullptr;
  picture_taker_ = nullptr;
  ResetBudget();
  lua_close(L_);
}

std::map<std::string, std::string> Scenario::ParseOverrides(const std::vector<std::string>& sets) {
  std::map<std::string, std::string> overrides;
  for (const auto& set : sets) {
    const size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--set " + set + ": write name=value");
    overrides[set.substr(0, eq)] = set.substr(eq + 1);
  }
  return overrides;
}

std::unique_ptr<Scenario> Scenario::Load(const std::string& path,
                                         const std::map<std::string, std::string>& overrides,
                                         uint64_t seed, Watchdog::Expiry on_hang) {
  static_assert(kNoRef == LUA_NOREF);
  std::unique_ptr<Scenario> s(new Scenario());
  s->file_ = path;
  if (on_hang) s->SetWatchdog(kScenarioCallWallTimeS, std::move(on_hang));
  s->rng_ = RngStream(seed, "scenario");
  s->chunk_ = {ReadTextFile(path), "@" + path};
  lua_State* L = s->L_ = lua_newstate(LuaMemory::Allocate, &s->memory_);
  UNIMOUSE_DEMAND(L != nullptr);
  // the API and the hook find their scenario here, from every thread of the state
  *static_cast<Scenario**>(lua_getextraspace(L)) = s.get();
  lua_sethook(L, CountInstructions, LUA_MASKCOUNT, kHookEvery);

  // from here on, every use of the Lua API is inside a protected call: whatever the file
  // returns, an error is a message, never a crash
  s->CallStep<OpenSandbox>(0, 0, "");
  s->CallStep<LoadChunk>(0, 1, "");
  try {
    s->Call(0, 1, "");
  } catch (const ScriptFault& fault) {
    s->RethrowWhileLoading(fault);
  }
  s->chunk_ = {};
  s->CallStep<KeepStages>(1, 0, "");

  // --set must name a declared parameter and fit its type
  for (const auto& [name, value] : overrides) {
    const auto declared = s->declared_.find(name);
    if (declared == s->declared_.end()) {
      std::string known;
      for (const auto& d : s->declared_) known += (known.empty() ? "" : ", ") + d.first;
      throw InputError("--set " + name + ": scenario '" + s->name_ + "' has no parameter '" + name +
                       "' (it has: " + (known.empty() ? "none" : known) + ")");
    }
    if (declared->second == "number") {
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(v)) {
        throw InputError("--set " + name + "=" + value + ": '" + name + "' is a number");
      }
    } else if (declared->second == "boolean" && value != "true" && value != "false") {
      throw InputError("--set " + name + "=" + value + ": '" + name + "' is true or false");
    }
    s->param_text_[name] = value;
  }
  s->overrides_ = overrides;
  s->CallStep<ApplyOverrides>(0, 0, "");
  return s;
}

int Scenario::OpenSandbox(LuaCall& call) {
  lua_State* L = call.state();
  Scenario& s = Of(L);
  luaL_openlibs(L);
  // the prelude's arguments: sim with its C++ functions, the empty sandbox, the host's functions
  const std::string_view prelude = PreludeSource();
  if (luaL_loadbufferx(L, prelude.data(), prelude.size(), kPreludeChunk, "t") != LUA_OK) {
    throw std::logic_error("the scenario prelude does not compile: " + ErrorText(L, -1));
  }
  lua_createtable(L, 0, static_cast<int>(ScenarioApiEntries().size()));
  for (const ApiEntry& e : ScenarioApiEntries()) {
    if (e.body == nullptr) continue;  // written in Lua, in the prelude
    PushLuaFunction(L, e.body, e.name, "sim.");
    lua_setfield(L, -2, e.name);
  }
  lua_newtable(L);
  lua_pushvalue(L, -1);
  s.env_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_createtable(L, 0, static_cast<int>(ScenarioHostEntries().size()));
  for (const ApiEntry& e : ScenarioHostEntries()) {
    PushLuaFunction(L, e.body, e.name);
    lua_setfield(L, -2, e.name);
  }
  // and the names of the functions that take a table, whose keys check_keys checks
  lua_newtable(L);
  lua_Integer tables = 0;
  for (const ApiEntry& e : ScenarioApiEntries()) {
    if (TableArgumentOf(e).position == 0) continue;
    lua_pushstring(L, e.name);
    lua_rawseti(L, -2, ++tables);
  }
  call.ProtectedCall(4, 1);
  const int internals = lua_gettop(L);
  s.dispatch_ref_ = RefField(L, internals, "dispatch");
  s.inspect_ref_ = RefField(L, internals, "inspect");
  s.apply_ref_ = RefField(L, internals, "apply");
  return 0;
}

int Scenario::LoadChunk(LuaCall& call) {
  lua_State* L = call.state();
  const Scenario& s = Of(L);
  if (luaL_loadbufferx(L, s.chunk_.text.data(), s.chunk_.text.size(), s.chunk_.name.c_str(), "t") !=
      LUA_OK) {
    throw ScriptError(ErrorText(L, -1), /*located=*/true);
  }
  // in the sandbox: a main chunk's one upvalue is its _ENV
  lua_rawgeti(L, LUA_REGISTRYINDEX, s.env_ref_);
  lua_setupvalue(L, -2, 1);
  return 1;
}

int Scenario::KeepStages(LuaCall& call) {
  lua_State* L = call.state();
  Scenario& s = Of(L);
  // the prelude reads the returned value (any metamethod runs there), and gives plain tables
  lua_settop(L, 1);
  lua_rawgeti(L, LUA_REGISTRYINDEX, s.inspect_ref_);
  lua_insert(L, 1);
  lua_pushstring(L, s.file_.c_str());
  call.ProtectedCall(2, 2);
  s.name_ = call.StringField(1, "name", "");
  s.params_ref_ = RefField(L, 1, "params");
  s.world_ref_ = RefField(L, 1, "world");
  s.run_ref_ = RefField(L, 1, "run");
  s.finish_ref_ = RefField(L, 1, "finish");
  s.min_robots_ = static_cast<int>(call.IntegerField(1, "robots", 1));
  // each parameter as {name, type, value as text}
  const auto count = static_cast<lua_Integer>(lua_rawlen(L, 2));
  for (lua_Integer i = 1; i <= count; ++i) {
    lua_rawgeti(L, 2, i);
    std::string fields[3];
    for (int f = 0; f < 3; ++f) {
      lua_rawgeti(L, -1, f + 1);
      fields[f] = ErrorText(L, -1);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    s.declared_[fields[0]] = fields[1];
    s.param_text_[fields[0]] = fields[2];
  }
  return 0;
}

int Scenario::ApplyOverrides(LuaCall& call) {
  lua_State* L = call.state();
  Scenario& s = Of(L);
  lua_rawgeti(L, LUA_REGISTRYINDEX, s.apply_ref_);
  lua_rawgeti(L, LUA_REGISTRYINDEX, s.params_ref_);
  // {{name, value}, ...}, each value of its parameter's type (Load has checked them)
  lua_createtable(L, static_cast<int>(s.overrides_.size()), 0);
  lua_Integer n = 0;
  for (const auto& [name, value] : s.overrides_) {
    lua_createtable(L, 2, 0);
    lua_pushstring(L, name.c_str());
    lua_rawseti(L, -2, 1);
    const std::string& type = s.declared_.at(name);
    if (type == "number") {
      // as Lua reads a numeral: "12" is an integer, as 12 in the file is, and "12.0" a float
      if (lua_stringtonumber(L, value.c_str()) == 0) {
        lua_pushnumber(L, std::strtod(value.c_str(), nullptr));
      }
    } else if (type == "boolean") {
      lua_pushboolean(L, value == "true");
    } else {
      lua_pushstring(L, value.c_str());
    }
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, ++n);
  }
  call.ProtectedCall(2, 1);
  s.time_limit_s_ = lua_tonumber(L, -1);

  // the values the run sees, with their types, for the result
  lua_rawgeti(L, LUA_REGISTRYINDEX, s.params_ref_);
  for (const auto& [name, text] : s.param_text_) {
    lua_pushstring(L, name.c_str());
    lua_rawget(L, -2);
    s.param_values_[name] = ScalarAt(L, -1).value_or(text);
    lua_pop(L, 1);
  }
  return 0;
}

int Scenario::Traceback(LuaCall& call) {
  lua_State* L = call.state();
  // an error value that is not text is named by its type
  if (lua_type(L, 1) != LUA_TSTRING) {
    lua_pushstring(L, ErrorText(L, 1).c_str());
    lua_replace(L, 1);
  }
  luaL_traceback(L, L, lua_tostring(L, 1), 1);
  return 1;
}

int Scenario::SpendInstructions(LuaCall& call) {
  // where the script is: in a hook, level 0 is the running function
  Of(call.state()).Spend(call.state(), 0, kHookEvery);
  return 0;
}

void Scenario::Spend(lua_State* L, int level, int64_t instructions) {
  if (Spent(L, level).empty()) {
    instructions_ += instructions;
    if (kernel_ != nullptr) run_instructions_ += instructions;
    const double allowed =
        kScenarioInstructionBudget +
        (kernel_ != nullptr ? kernel_->state().data().time * kScenarioInstructionsPerSecond : 0);
    if (instructions_ <= kScenarioInstructionBudget &&
        static_cast<double>(run_instructions_) <= allowed) {
      return;
    }
    budget_error_ =
        ScriptLine(L, level) + "instruction budget exhausted: " +
        (instructions_ > kScenarioInstructionBudget
             ? "more than " + std::to_string(std::lround(kScenarioInstructionBudget / 1e6)) +
                   " million instructions in one call into the script, its limit per call (a "
                   "loop that never waits? use sim.wait)"
             : "more than " + std::to_string(std::lround(kScenarioInstructionsPerSecond / 1e6)) +
                   " million instructions per simulated second on average");
  }
  // once spent, the budget raises at every hook until the host is back in control
  throw ScriptError(budget_error_, /*located=*/true);
}

const std::string& Scenario::Spent(lua_State* L, int level) {
  if (budget_error_.empty() && memory_.volume_spent()) {
    budget_error_ = ScriptLine(L, level) + AllocationsSpent();
  }
  return budget_error_;
}

void Scenario::CountInstructions(lua_State* L, lua_Debug*) {
  RunBody(L, SpendInstructions, "the instruction budget");
}

void Scenario::ResetBudget() {
  instructions_ = 0;
  budget_error_.clear();
  memory_.ResetVolume();
}

int Scenario::RunScript(lua_State* thread, int nargs, int nresults, int handler, const char* what,
                        int* nres) {
  ResetBudget();
  watchdog_.Arm(*what != '\0' ? what : "loading");
  memory_.SetScriptRunning(true);
  const int status = nres != nullptr ? lua_resume(thread, L_, nargs, nres)
                                     : lua_pcall(thread, nargs, nresults, handler);
  memory_.SetScriptRunning(false);
  watchdog_.Disarm();
  return status;
}

std::string Scenario::ErrorOf(lua_State* thread, int status) const {
  const std::string message = ErrorText(thread, -1);
  // a memory error has no place, only Lua's words (the prelude's wrappers pass them on as text):
  // say which limit it met, keeping any traceback
  if (status != LUA_ERRMEM && Headline(message) != "not enough memory") return message;
  const std::string rest = message.substr(Headline(message).size());
  if (!budget_error_.empty()) return budget_error_ + rest;
  if (memory_.volume_spent()) return AllocationsSpent() + rest;
  return "not enough memory: a scenario holds at most " +
         std::to_string(kScenarioMemoryBytes >> 20) + " MiB" + rest;
}

void Scenario::SnapshotOn(const std::string& kind, const std::string& camera, int width,
                          int height) {
  static constexpr const char* kChunk = R"lua(
local kind, picture = ...
local n = 0
sim.on(kind, function()
  n = n + 1
  sim.snapshot_save(string.format("events/%s_%04d.png", kind, n), picture)
end)
)lua";
  lua_State* L = L_;
  UNIMOUSE_DEMAND(luaL_loadbufferx(L, kChunk, std::strlen(kChunk), "=snapshot_on", "t") == LUA_OK);
  lua_rawgeti(L, LUA_REGISTRYINDEX, env_ref_);
  lua_setupvalue(L, -2, 1);
  lua_pushstring(L, kind.c_str());
  lua_createtable(L, 0, 3);
  lua_pushstring(L, camera.c_str());
  lua_setfield(L, -2, "camera");
  lua_pushinteger(L, width);
  lua_setfield(L, -2, "width");
  lua_pushinteger(L, height);
  lua_setfield(L, -2, "height");
  if (RunScript(L, 2, 0, 0, "--snapshot-on") != LUA_OK) {
    lua_pop(L, 1);
    throw InputError("--snapshot-on " + kind +
                     ": not an event; the events are cell_entered, wall_contact, gate_crossed, "
                     "firmware_log and firmware_restart");
  }
}

void Scenario::Call(int nargs, int nresults, const char* what) {
  // under the function: the message handler, which adds the traceback
  const int handler = lua_gettop(L_) - nargs;
  lua_pushcfunction(L_, HostStep<Traceback>);
  lua_insert(L_, handler);
  const int status = RunScript(L_, nargs, nresults, handler, what);
  lua_remove(L_, handler);
  if (status != LUA_OK) {
    const std::string message = ErrorOf(L_, status);
    lua_settop(L_, 0);
    Throw(message, what);
  }
}

template <int (*kStep)(LuaCall&)>
void Scenario::CallStep(int nargs, int nresults, const char* what) {
  lua_pushcfunction(L_, HostStep<kStep>);
  lua_insert(L_, -nargs - 1);
  Call(nargs, nresults, what);
}

void Scenario::Throw(const std::string& traceback, const char* what) {
  traceback_ = traceback;
  if (kernel_ != nullptr) kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", traceback);
  throw ScriptFault(Headline(traceback) + (*what != '\0' ? " (in " + std::string(what) + ")" : ""),
                    traceback);
}

bool Scenario::ReturnsFunction(const std::string& path) {
  std::unique_ptr<Scenario> s(new Scenario());
  s->file_ = path;
  s->rng_ = RngStream(1, "scenario");
  s->chunk_ = {ReadTextFile(path), "@" + path};
  lua_State* L = s->L_ = lua_newstate(LuaMemory::Allocate, &s->memory_);
  UNIMOUSE_DEMAND(L != nullptr);
  *static_cast<Scenario**>(lua_getextraspace(L)) = s.get();
  lua_sethook(L, CountInstructions, LUA_MASKCOUNT, kHookEvery);
  // as Load does, up to what the file returns
  s->CallStep<OpenSandbox>(0, 0, "");
  s->CallStep<LoadChunk>(0, 1, "");
  s->Call(0, 1, "");
  return lua_isfunction(L, -1);
}

void Scenario::RethrowWhileLoading(const ScriptFault& fault) const {
  if (!bad_input_.empty()) throw InputError(bad_input_);
  if (!unknown_key_.empty() &&
      std::string_view(fault.what()).find(unknown_key_) != std::string_view::npos) {
    throw InputError(fault.what());
  }
  throw;
}

ScenarioWorld Scenario::BuildWorld() {
  if (world_ref_ != LUA_REFNIL) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, world_ref_);
    lua_rawgeti(L_, LUA_REGISTRYINDEX, params_ref_);
    try {
      Call(1, 0, "world");
    } catch (const ScriptFault& fault) {
      RethrowWhileLoading(fault);
    }
  }
  return std::move(world_);
}

void Scenario::Attach(Kernel& kernel, const std::string& controller) {
  std::vector<std::string> controllers(static_cast<size_t>(kernel.robot_count()));
  controllers[0] = controller;
  Attach(kernel, controllers);
}

void Scenario::Attach(Kernel& kernel, const std::vector<std::string>& controllers) {
  kernel_ = &kernel;
  coroutine_ = lua_newthread(L_);
  coroutine_ref_ = luaL_ref(L_, LUA_REGISTRYINDEX);
  for (size_t robot = 0; robot < controllers.size(); ++robot) {
    const std::string& controller = controllers[robot];
    if (controller.empty()) continue;
    // the controller file runs in the scenario's sandbox, with the same sim API, for its robot
    chunk_ = {ReadTextFile(controller), "@" + controller};
    CallStep<LoadChunk>(0, 1, "");
    chunk_ = {};
    Call(0, 1, "");
    if (!lua_isfunction(L_, -1)) {
      lua_settop(L_, 0);
      throw RuntimeFault(controller + ": a controller file returns function(time_s) ... end");
    }
    controllers_.push_back({static_cast<int>(robot), luaL_ref(L_, LUA_REGISTRYINDEX)});
  }
  kernel.AddMessageListener(
      [this](double time_s, int level, const std::string&, const std::string& message) {
        if (level == UNIMOUSE_LOG_FIRMWARE) firmware_lines_.emplace_back(time_s, message);
      });
  kernel.AddReportListener([this](const std::string&, int robot, const unimouse_report& report) {
    if (report.kind == UNIMOUSE_REPORT_RESTART) {
      firmware_restarts_.push_back(
          {kernel_->state().data().time, static_cast<int>(report.value), robot});
    }
  });
  kernel.SetBoundaryHook([this] { Tick(); });
}

void Scenario::Tick() {
  if (!finished() && started_) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, dispatch_ref_);
    Call(0, 0, "an event handler");
  }
  if (!finished()) {
    // the first resume starts run(params); later ones continue it after its yield
    int nargs = 0;
    if (!started_) {
      started_ = true;
      lua_rawgeti(coroutine_, LUA_REGISTRYINDEX, run_ref_);
      lua_rawgeti(coroutine_, LUA_REGISTRYINDEX, params_ref_);
      nargs = 1;
    }
    if (lua_status(coroutine_) == LUA_YIELD || nargs == 1) {
      int nres = 0;
      const int status = RunScript(coroutine_, nargs, 0, 0, "run", &nres);
      if (status != LUA_OK && status != LUA_YIELD) {
        const std::string message = ErrorOf(coroutine_, status);
        luaL_traceback(L_, coroutine_, message.c_str(), 0);
        const std::string traceback = lua_tostring(L_, -1);
        lua_settop(L_, 0);
        Throw(traceback, "run");
      }
      lua_pop(coroutine_, nres);
      if (status == LUA_OK && !finished()) {
        outcome_.status = "failed";
        outcome_.reason = "run ended without sim.pass or sim.fail";
      }
    }
  }
  for (const auto& [robot, ref] : controllers_) {
    // a controller's sim.* calls are about its own robot
    current_robot_ = robot;
    lua_rawgeti(L_, LUA_REGISTRYINDEX, ref);
    lua_pushnumber(L_, kernel_->state().data().time);
    Call(1, 0, "the controller");
  }
  current_robot_ = 0;
}

void Scenario::Finish() {
  if (finish_called_) return;
  finish_called_ = true;
  if (finish_ref_ == LUA_REFNIL) return;
  lua_rawgeti(L_, LUA_REGISTRYINDEX, finish_ref_);
  lua_rawgeti(L_, LUA_REGISTRYINDEX, params_ref_);
  lua_createtable(L_, 0, 3);
  lua_pushstring(L_, outcome_.status.c_str());
  lua_setfield(L_, -2, "status");
  lua_pushstring(L_, outcome_.reason.c_str());
  lua_setfield(L_, -2, "reason");
  lua_pushnumber(L_, kernel_->state().data().time);
  lua_setfield(L_, -2, "time_s");
  Call(2, 0, "finish");
}

}  // namespace unimouse
