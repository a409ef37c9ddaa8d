// SPDX-License-Identifier: GPL-3.0-or-later
#include "scenario.h"

#include <lua5.4/lauxlib.h>
#include <lua5.4/lua.h>
#include <lua5.4/lualib.h>

#include <cmath>
#include <cstring>

#include "scenario_api.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {

namespace {

constexpr int kBudget = 20'000'000;  // instructions between two yields
constexpr int kHookEvery = 1000;
int instructions = 0;

void CountInstructions(lua_State* L, lua_Debug*) {
  instructions += kHookEvery;
  if (instructions > kBudget) {
    instructions = 0;
    // where the script is: level 0 in a hook is the running Lua function
    lua_Debug ar;
    std::string where;
    if (lua_getstack(L, 0, &ar) && lua_getinfo(L, "Sl", &ar) && ar.source[0] == '@') {
      where = std::string(ar.source + 1) + ":" + std::to_string(ar.currentline) + ": ";
    }
    lua_pushstring(L, (where + "instruction budget exhausted: a loop that never waits "
                               "(use sim.wait)?")
                          .c_str());
    lua_error(L);
  }
}

// waits, in Lua: one yield per tick
constexpr const char* kPrelude = R"lua(
local sim, yield, take_firmware_lines = ...
function sim.next_tick() yield() end

-- walls from many straight pieces
function sim.wall_polyline(w)
  assert(type(w) == "table" and type(w.points) == "table" and #w.points >= 2,
         "sim.wall_polyline{points = {{x_m, y_m}, ...}}: at least two points")
  for i = 1, #w.points - 1 do
    local a, b = w.points[i], w.points[i + 1]
    sim.wall_add { x1_m = a[1], y1_m = a[2], x2_m = b[1], y2_m = b[2],
                   thickness_m = w.thickness_m, height_m = w.height_m }
  end
end
function sim.wall_arc(w)
  assert(type(w) == "table" and w.cx_m and w.cy_m and w.radius_m and w.from_deg and w.to_deg,
         "sim.wall_arc{cx_m, cy_m, radius_m, from_deg, to_deg}")
  local n = w.segments or math.max(1, math.ceil(math.abs(w.to_deg - w.from_deg) / 10))
  local points = {}
  for i = 0, n do
    local a = math.rad(w.from_deg + (w.to_deg - w.from_deg) * i / n)
    points[#points + 1] = { w.cx_m + w.radius_m * math.cos(a), w.cy_m + w.radius_m * math.sin(a) }
  end
  sim.wall_polyline { points = points, thickness_m = w.thickness_m, height_m = w.height_m }
end

-- events, checked once a tick at the boundary, before run resumes, in the order added
local handlers, gates = {}, {}
function sim.on(kind, handler)
  assert(kind == "cell_entered" or kind == "wall_contact" or kind == "gate_crossed"
         or kind == "firmware_log",
         "sim.on: unknown event '" .. tostring(kind) .. "'")
  handlers[kind] = handlers[kind] or {}
  table.insert(handlers[kind], handler)
end
function sim.gate_add(g)
  assert(type(g) == "table" and g.name and g.x1_m and g.y1_m and g.x2_m and g.y2_m,
         "sim.gate_add{name, x1_m, y1_m, x2_m, y2_m}")
  table.insert(gates, g)
end
local last_cell, touching, last_pose
local function fire(kind, event)
  for _, handler in ipairs(handlers[kind] or {}) do handler(event) end
end
local function dispatch()
  local now = sim.time()
  for _, line in ipairs(take_firmware_lines()) do fire("firmware_log", line) end
  if handlers.cell_entered then
    local c = sim.robot_get_cell()
    if not last_cell or c.x ~= last_cell.x or c.y ~= last_cell.y then
      fire("cell_entered", { x = c.x, y = c.y, time_s = now })
    end
    last_cell = c
  end
  if handlers.wall_contact then
    local t = sim.robot_is_touching_wall()
    if t and not touching then fire("wall_contact", { time_s = now }) end
    touching = t
  end
  if handlers.gate_crossed then
    local p = sim.robot_get_pose()
    for _, g in ipairs(last_pose and gates or {}) do
      -- the centre's path since the last tick against the gate: which side before and after
      local gx, gy = g.x2_m - g.x1_m, g.y2_m - g.y1_m
      local before = gx * (last_pose.y_m - g.y1_m) - gy * (last_pose.x_m - g.x1_m)
      local after = gx * (p.y_m - g.y1_m) - gy * (p.x_m - g.x1_m)
      if (before < 0) ~= (after < 0) then
        local mx, my = p.x_m - last_pose.x_m, p.y_m - last_pose.y_m
        local t0 = ((g.x1_m - last_pose.x_m) * my - (g.y1_m - last_pose.y_m) * mx) / (mx * gy - my * gx)
        if t0 >= 0 and t0 <= 1 then
          -- +1 when crossing from the gate's right side to its left, looking from 1 to 2
          fire("gate_crossed", { name = g.name, direction = after > 0 and 1 or -1, time_s = now })
        end
      end
    end
    last_pose = p
  end
end
function sim.wait(seconds)
  local until_s = sim.time() + seconds - 1e-9
  while sim.time() < until_s do yield() end
end
function sim.wait_until(condition, options)
  local timeout_s = options and options.timeout_s
  local start_s = sim.time()
  while not condition() do
    if timeout_s and sim.time() - start_s >= timeout_s then return false end
    yield()
  end
  return true
end
return dispatch
)lua";

// first line of a Lua error, which starts with file:line
std::string Headline(const std::string& message) { return message.substr(0, message.find('\n')); }

}  // namespace

Scenario::~Scenario() {
  if (L_ != nullptr) lua_close(L_);
}

std::unique_ptr<Scenario> Scenario::Load(const std::string& path,
                                         const std::map<std::string, std::string>& overrides,
                                         uint64_t seed) {
  std::unique_ptr<Scenario> s(new Scenario());
  s->file_ = path;
  s->seed_ = seed;
  const std::string text = ReadTextFile(path);
  lua_State* L = s->L_ = luaL_newstate();
  UNIMOUSE_DEMAND(L != nullptr);
  luaL_openlibs(L);
  lua_pushlightuserdata(L, s.get());
  lua_setfield(L, LUA_REGISTRYINDEX, "unimouse.scenario");
  auto* rng = static_cast<RngStream*>(lua_newuserdatauv(L, sizeof(RngStream), 0));
  new (rng) RngStream(seed, "scenario");
  lua_setfield(L, LUA_REGISTRYINDEX, "unimouse.rng");
  lua_sethook(L, CountInstructions, LUA_MASKCOUNT, kHookEvery);

  // the sandbox: a fresh environment with the safe parts of the standard library
  lua_newtable(L);
  const int env = lua_gettop(L);
  for (const char* name :
       {"assert",   "error",        "ipairs",       "pairs",  "next",     "select", "tostring",
        "tonumber", "type",         "pcall",        "xpcall", "rawequal", "rawget", "rawlen",
        "rawset",   "setmetatable", "getmetatable", "string", "table",    "utf8",   "coroutine"}) {
    lua_getglobal(L, name);
    lua_setfield(L, env, name);
  }
  lua_newtable(L);  // math, with the seeded random
  lua_getglobal(L, "math");
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_settable(L, -5);
  }
  lua_pop(L, 1);
  lua_pushcfunction(L, ScenarioSandboxFunctions().random);
  lua_setfield(L, -2, "random");
  lua_pushnil(L);
  lua_setfield(L, -2, "randomseed");
  lua_setfield(L, env, "math");
  lua_pushcfunction(L, ScenarioSandboxFunctions().print);
  lua_setfield(L, env, "print");

  lua_createtable(L, 0, static_cast<int>(ScenarioApiEntries().size()));
  for (const ApiEntry& e : ScenarioApiEntries()) {
    if (e.fn == nullptr) continue;  // written in Lua, in the prelude
    lua_pushcfunction(L, e.fn);
    lua_setfield(L, -2, e.name);
  }
  const int sim = lua_gettop(L);
  lua_pushvalue(L, sim);
  lua_setfield(L, env, "sim");
  if (luaL_loadbufferx(L, kPrelude, std::strlen(kPrelude), "=prelude", "t") != LUA_OK) {
    std::fprintf(stderr, "%s\n", lua_tostring(L, -1));
    UNIMOUSE_DEMAND(!"the scenario prelude compiles");
  }
  lua_pushvalue(L, sim);
  lua_getglobal(L, "coroutine");
  lua_getfield(L, -1, "yield");
  lua_remove(L, -2);
  lua_pushcfunction(L, ScenarioSandboxFunctions().take_firmware_lines);
  if (lua_pcall(L, 3, 1, 0) != LUA_OK) {
    std::fprintf(stderr, "%s\n", lua_tostring(L, -1));
    UNIMOUSE_DEMAND(!"the scenario prelude runs");
  }
  s->dispatch_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_pop(L, 1);  // sim

  // the scenario file, in the sandbox, text only
  if (luaL_loadbufferx(L, text.data(), text.size(), ("@" + path).c_str(), "t") != LUA_OK) {
    throw RuntimeFault(Headline(lua_tostring(L, -1)));
  }
  lua_pushvalue(L, env);
  lua_setfield(L, LUA_REGISTRYINDEX, "unimouse.env");
  lua_pushvalue(L, env);
  lua_setupvalue(L, -2, 1);
  instructions = 0;
  if (lua_pcall(L, 0, 1, 0) != LUA_OK) throw RuntimeFault(Headline(lua_tostring(L, -1)));
  if (!lua_istable(L, -1)) {
    throw RuntimeFault(path + ": a scenario file returns sim.scenario { name = ..., run = ... }");
  }
  lua_getfield(L, -1, "name");
  s->name_ = lua_tostring(L, -1);
  lua_pop(L, 1);

  // parameters: the declared defaults, then --set, which must name one and fit its type
  lua_getfield(L, -1, "params");
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    lua_newtable(L);
  }
  std::vector<std::string> declared;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    declared.push_back(lua_tostring(L, -2));
    s->param_text_[declared.back()] = luaL_tolstring(L, -1, nullptr);
    lua_pop(L, 2);
  }
  for (const auto& [name, value] : overrides) {
    lua_getfield(L, -1, name.c_str());
    const int type = lua_type(L, -1);
    lua_pop(L, 1);
    if (type == LUA_TNIL) {
      std::string known;
      for (const auto& d : declared) known += (known.empty() ? "" : ", ") + d;
      throw InputError("--set " + name + ": scenario '" + s->name_ + "' has no parameter '" + name +
                       "' (it has: " + (known.empty() ? "none" : known) + ")");
    }
    if (type == LUA_TNUMBER) {
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(v)) {
        throw InputError("--set " + name + "=" + value + ": '" + name + "' is a number");
      }
      lua_pushnumber(L, v);
    } else if (type == LUA_TBOOLEAN) {
      if (value != "true" && value != "false") {
        throw InputError("--set " + name + "=" + value + ": '" + name + "' is true or false");
      }
      lua_pushboolean(L, value == "true");
    } else {
      lua_pushstring(L, value.c_str());
    }
    lua_setfield(L, -2, name.c_str());
    s->param_text_[name] = value;
  }
  lua_getfield(L, -1, "time_limit_s");
  s->time_limit_s_ = lua_isnumber(L, -1) ? lua_tonumber(L, -1) : 0;
  lua_pop(L, 1);
  s->params_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  s->scenario_ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_settop(L, 0);
  return s;
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
  lua_getfield(L, LUA_REGISTRYINDEX, "unimouse.env");
  lua_setupvalue(L, -2, 1);
  lua_pushstring(L, kind.c_str());
  lua_createtable(L, 0, 3);
  lua_pushstring(L, camera.c_str());
  lua_setfield(L, -2, "camera");
  lua_pushinteger(L, width);
  lua_setfield(L, -2, "width");
  lua_pushinteger(L, height);
  lua_setfield(L, -2, "height");
  if (lua_pcall(L, 2, 0, 0) != LUA_OK) {
    lua_pop(L, 1);
    throw InputError("--snapshot-on " + kind +
                     ": not an event; the events are cell_entered, wall_contact, gate_crossed and "
                     "firmware_log");
  }
}

void Scenario::Call(int nargs, const char* what) {
  lua_getglobal(L_, "debug");
  lua_getfield(L_, -1, "traceback");
  lua_remove(L_, -2);
  const int handler = lua_gettop(L_) - nargs - 1;
  lua_insert(L_, handler);
  instructions = 0;
  if (lua_pcall(L_, nargs, 0, handler) != LUA_OK) {
    const std::string message = lua_tostring(L_, -1);
    lua_settop(L_, 0);
    Throw(message, what);
  }
  lua_settop(L_, 0);
}

void Scenario::Throw(const std::string& traceback, const char* what) {
  traceback_ = traceback;
  if (kernel_ != nullptr) kernel_->Log(UNIMOUSE_LOG_INFO, "scenario", traceback);
  throw RuntimeFault(Headline(traceback) + " (in " + what + ")");
}

ScenarioWorld Scenario::BuildWorld() {
  lua_rawgeti(L_, LUA_REGISTRYINDEX, scenario_ref_);
  lua_getfield(L_, -1, "world");
  lua_remove(L_, -2);
  if (lua_isfunction(L_, -1)) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, params_ref_);
    Call(1, "world");
  } else {
    lua_settop(L_, 0);
  }
  return std::move(world_);
}

void Scenario::Attach(Kernel& kernel, const std::string& controller) {
  kernel_ = &kernel;
  coroutine_ = lua_newthread(L_);
  coroutine_ref_ = luaL_ref(L_, LUA_REGISTRYINDEX);
  if (!controller.empty()) {
    // the controller file runs in the scenario's sandbox, with the same sim API
    const std::string text = ReadTextFile(controller);
    if (luaL_loadbufferx(L_, text.data(), text.size(), ("@" + controller).c_str(), "t") != LUA_OK) {
      throw RuntimeFault(Headline(lua_tostring(L_, -1)));
    }
    lua_getfield(L_, LUA_REGISTRYINDEX, "unimouse.env");
    lua_setupvalue(L_, -2, 1);
    instructions = 0;
    if (lua_pcall(L_, 0, 1, 0) != LUA_OK) throw RuntimeFault(Headline(lua_tostring(L_, -1)));
    if (!lua_isfunction(L_, -1)) {
      throw RuntimeFault(controller + ": a controller file returns function(time_s) ... end");
    }
    controller_ref_ = luaL_ref(L_, LUA_REGISTRYINDEX);
  }
  kernel.AddMessageListener(
      [this](double time_s, int level, const std::string&, const std::string& message) {
        if (level == UNIMOUSE_LOG_FIRMWARE) firmware_lines_.emplace_back(time_s, message);
      });
  kernel.SetBoundaryHook([this] { Tick(); });
}

void Scenario::Tick() {
  if (!finished() && started_) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, dispatch_ref_);
    Call(0, "an event handler");
  }
  if (!finished()) {
    // the first resume starts run(params); later ones continue it after its yield
    int nargs = 0;
    if (!started_) {
      started_ = true;
      lua_rawgeti(coroutine_, LUA_REGISTRYINDEX, scenario_ref_);
      lua_getfield(coroutine_, -1, "run");
      lua_remove(coroutine_, -2);
      lua_rawgeti(coroutine_, LUA_REGISTRYINDEX, params_ref_);
      nargs = 1;
    }
    if (lua_status(coroutine_) == LUA_YIELD || nargs == 1) {
      int nres = 0;
      instructions = 0;
      const int status = lua_resume(coroutine_, L_, nargs, &nres);
      if (status != LUA_OK && status != LUA_YIELD) {
        luaL_traceback(L_, coroutine_, lua_tostring(coroutine_, -1), 0);
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
  if (controller_ref_ >= 0) {
    lua_rawgeti(L_, LUA_REGISTRYINDEX, controller_ref_);
    lua_pushnumber(L_, kernel_->state().data().time);
    Call(1, "the controller");
  }
}

void Scenario::Finish() {
  if (finish_called_) return;
  finish_called_ = true;
  lua_rawgeti(L_, LUA_REGISTRYINDEX, scenario_ref_);
  lua_getfield(L_, -1, "finish");
  lua_remove(L_, -2);
  if (!lua_isfunction(L_, -1)) {
    lua_settop(L_, 0);
    return;
  }
  lua_rawgeti(L_, LUA_REGISTRYINDEX, params_ref_);
  lua_createtable(L_, 0, 3);
  lua_pushstring(L_, outcome_.status.c_str());
  lua_setfield(L_, -2, "status");
  lua_pushstring(L_, outcome_.reason.c_str());
  lua_setfield(L_, -2, "reason");
  lua_pushnumber(L_, kernel_->state().data().time);
  lua_setfield(L_, -2, "time_s");
  Call(2, "finish");
}

}  // namespace unimouse
