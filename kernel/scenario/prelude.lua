-- SPDX-License-Identifier: GPL-3.0-or-later
-- The scenario prelude: the sandbox a scenario runs in, the parts of the sim API written in Lua,
-- and the host's own steps in Lua. The library carries this file (nothing is read at run time);
-- each scenario's Lua state runs it once, with the sim table (its C++ functions in place), the
-- empty sandbox, the host's functions and the names of the sim functions that take a table, and
-- keeps the table it returns.
--
-- A helper blames a bad argument on its caller, error(message, 2), so that the message names
-- the scenario's file:line; errors raised in C++ skip this file's frames the same way.
local sim, env, host, table_taking = ...

-- scripts share the string and table libraries: keep what this file needs from them
local format, insert = string.format, table.insert
local yield = coroutine.yield

local function copy(library)
  local t = {}
  for k, v in pairs(library) do t[k] = v end
  return t
end

-- the sandbox: the safe parts of the standard library; no io, os, load, dofile or require
for _, name in ipairs { "assert", "error", "ipairs", "pairs", "next", "select", "tostring",
                        "tonumber", "type", "rawequal", "rawget", "rawlen", "rawset",
                        "getmetatable" } do
  env[name] = _G[name]
end

-- work done inside C, where the instruction count does not see it, stays bounded. A finalizer
-- (__gc) runs with no count at all, so no table gets one; n empty copies are nothing, made
-- here rather than n times in C; the elements table.move copies, table.insert and
-- table.remove shift and table.sort orders count as instructions. Whatever C builds is
-- allocated, and the allocations are counted too.
local setmetatable, rep = setmetatable, string.rep
local move, tinsert, tremove, sort = table.move, table.insert, table.remove, table.sort
local charge = host.charge
local function size(t) return type(t) == "table" and rawlen(t) or 0 end
local function after(t, pos) return math.type(pos) and math.max(size(t) - pos, 0) or 0 end
-- the results of pcall(library function, ...) for the wrapper `name`, tail-called in its
-- place: an error the library raised itself has no place (pcall called it), so it gets the
-- script's line and the name the script called; a memory error and the script's own errors
-- pass on as they are
local function relay(name, ok, ...)
  if ok then return ... end
  local message = ...
  if type(message) == "string" and message ~= "not enough memory" and
     not message:find("^[^\n]-:%d+: ") then
    error((message:gsub("to '%?'", "to '" .. name .. "'", 1)), 2)
  end
  error(message, 0)
end
function env.setmetatable(t, metatable)
  if type(metatable) == "table" and rawget(metatable, "__gc") ~= nil then
    error("setmetatable: __gc (a finalizer) is not available to scenarios", 2)
  end
  return relay("setmetatable", pcall(setmetatable, t, metatable))
end
function string.rep(s, n, sep)
  if s == "" and (sep == nil or sep == "") and math.type(n) then return "" end
  return relay("string.rep", pcall(rep, s, n, sep))
end
function table.move(a1, f, e, t, a2)
  if math.type(f) and math.type(e) and e >= f then charge(e * 1.0 - f + 1) end
  return relay("table.move", pcall(move, a1, f, e, t, a2))
end
function table.insert(t, ...)
  if select("#", ...) >= 2 then charge(after(t, ...)) end
  return relay("table.insert", pcall(tinsert, t, ...))
end
function table.remove(t, ...)
  if select("#", ...) >= 1 then charge(after(t, ...)) end
  return relay("table.remove", pcall(tremove, t, ...))
end
function table.sort(t, ...)
  charge(size(t))
  return relay("table.sort", pcall(sort, t, ...))
end

-- patterns: string.find and string.match are the host's, with every step of the matcher
-- counted; string.gmatch and string.gsub are built here on the host's search
local search, pack, unpack, gsub = host.pattern_search, table.pack, table.unpack, string.gsub
local function text(value, arg, name)
  local kind = type(value)
  if kind == "string" then return value end
  if kind == "number" then return tostring(value) end
  error(format("bad argument #%d to '%s' (string expected, got %s)", arg, name,
               value == nil and "no value" or kind), 3)
end
local function start(init, length)  -- as Lua reads a start position, 1-based
  if init > 0 then return init end
  if init == 0 or init < -length then return 1 end
  return length + init + 1
end
string.find, string.match = host["string.find"], host["string.match"]
function string.gmatch(s, pattern, init)
  s, pattern = text(s, 1, "string.gmatch"), text(pattern, 2, "string.gmatch")
  if init ~= nil and math.type(init) ~= "integer" then
    error("bad argument #3 to 'string.gmatch' (number has no integer representation)", 2)
  end
  local from, skip = math.min(start(init or 1, #s), #s + 1), 0
  return function()
    local found = pack(search(s, pattern, from, false, skip))
    if found[1] == nil then return nil end
    from, skip = found[2] + 1, found[2] + 1
    if found.n > 2 then return unpack(found, 3, found.n) end
    return s:sub(found[1], found[2])
  end
end
function string.gsub(s, pattern, replacement, most)
  s, pattern = text(s, 1, "string.gsub"), text(pattern, 2, "string.gsub")
  local kind = type(replacement)
  if kind == "number" then replacement, kind = tostring(replacement), "string" end
  if kind ~= "string" and kind ~= "table" and kind ~= "function" then
    error(format("bad argument #3 to 'string.gsub' (string/function/table expected, got %s)",
                 replacement == nil and "no value" or kind), 2)
  end
  if most ~= nil and math.type(most) ~= "integer" then
    error("bad argument #4 to 'string.gsub' (number expected, got " .. type(most) .. ")", 2)
  end
  most = most or math.maxinteger
  local anchored = pattern:sub(1, 1) == "^"
  if anchored then pattern = pattern:sub(2) end
  local parts, count, from, skip = {}, 0, 1, 0
  while count < most do
    local found = pack(search(s, pattern, from, anchored, skip))
    if found[1] == nil then break end
    local whole = s:sub(found[1], found[2])
    local first = found.n > 2 and found[3] or whole
    local value
    if kind == "string" then
      value = gsub(replacement, "%%(.?)", function(c)
        if c == "%" then return "%" end
        local index = tonumber(c)
        if c == "" or index == nil or math.type(index) ~= "integer" then
          error("invalid use of '%' in replacement string", 4)
        end
        if index == 0 or (index == 1 and found.n == 2) then return whole end
        if index + 2 > found.n then
          error(format("invalid capture index %%%d in replacement string", index), 4)
        end
        return tostring(found[index + 2])
      end)
    elseif kind == "table" then
      value = replacement[first]
    elseif found.n > 2 then
      value = replacement(unpack(found, 3, found.n))
    else
      value = replacement(whole)
    end
    if value == nil or value == false then
      value = whole
    elseif type(value) ~= "string" and type(value) ~= "number" then
      error("invalid replacement value (a " .. type(value) .. ")", 2)
    end
    parts[#parts + 1] = s:sub(from, found[1] - 1)
    parts[#parts + 1] = value
    count = count + 1
    from, skip = found[2] + 1, found[2] + 1
    if anchored then break end
  end
  parts[#parts + 1] = s:sub(from)
  return table.concat(parts), count
end
env.string, env.table, env.utf8 = string, table, utf8
env.math = copy(math)
env.math.random, env.math.randomseed = host.random, nil  -- from the run's seed
env.print = host.print  -- to the run's log
env.sim = sim

-- a spent instruction budget cannot be caught: whatever catches errors passes it on
local function unless_spent(...)
  local spent = host.budget_spent()
  if spent then error(spent, 0) end
  return ...
end
function env.pcall(...) return unless_spent(pcall(...)) end
function env.xpcall(...) return unless_spent(xpcall(...)) end
env.coroutine = copy(coroutine)
function env.coroutine.resume(...) return unless_spent(coroutine.resume(...)) end
function env.coroutine.close(...) return unless_spent(coroutine.close(...)) end

-- waiting: one yield per tick
function sim.next_tick() yield() end
function sim.wait(seconds)
  if tonumber(seconds) == nil then error("sim.wait(seconds): seconds is a number", 2) end
  local until_s = sim.time() + seconds - 1e-9
  while sim.time() < until_s do yield() end
end
function sim.wait_until(condition, options)
  if type(condition) ~= "function" then
    error("sim.wait_until(condition, {timeout_s?}): condition is a function", 2)
  end
  if options ~= nil and type(options) ~= "table" then
    error("sim.wait_until(condition, {timeout_s?}): options is a table", 2)
  end
  local timeout_s = options and options.timeout_s
  local start_s = sim.time()
  while not condition() do
    if timeout_s and sim.time() - start_s >= timeout_s then return false end
    yield()
  end
  return true
end

-- walls from many straight pieces
function sim.wall_polyline(w)
  if type(w) ~= "table" or type(w.points) ~= "table" or #w.points < 2 then
    error("sim.wall_polyline{points = {{x_m, y_m}, ...}}: at least two points", 2)
  end
  local points = w.points
  for i = 1, #points do
    local p = points[i]
    if type(p) ~= "table" or tonumber(p[1]) == nil or tonumber(p[2]) == nil then
      error(format("sim.wall_polyline: point %d is not {x_m, y_m}", i), 2)
    end
  end
  for i = 1, #points - 1 do
    local a, b = points[i], points[i + 1]
    sim.wall_add { x1_m = a[1], y1_m = a[2], x2_m = b[1], y2_m = b[2],
                   thickness_m = w.thickness_m, height_m = w.height_m }
  end
end
function sim.wall_arc(w)
  if type(w) ~= "table" then error("sim.wall_arc{cx_m, cy_m, radius_m, from_deg, to_deg}", 2) end
  for _, key in ipairs { "cx_m", "cy_m", "radius_m", "from_deg", "to_deg" } do
    if tonumber(w[key]) == nil then error(format("sim.wall_arc: field '%s' is a number", key), 2) end
  end
  local n = math.tointeger(w.segments or
                           math.max(1, math.ceil(math.abs(w.to_deg - w.from_deg) / 10)))
  if n == nil or n < 1 then
    error("sim.wall_arc: segments is a whole number, at least 1", 2)
  end
  local points = {}
  for i = 0, n do
    local a = math.rad(w.from_deg + (w.to_deg - w.from_deg) * i / n)
    points[#points + 1] = { w.cx_m + w.radius_m * math.cos(a), w.cy_m + w.radius_m * math.sin(a) }
  end
  sim.wall_polyline { points = points, thickness_m = w.thickness_m, height_m = w.height_m }
end

-- events, checked once a tick at the boundary, before run resumes, in the order added
local kinds = { cell_entered = true, wall_contact = true, gate_crossed = true, firmware_log = true,
                firmware_restart = true }
local handlers, gates = {}, {}
function sim.on(kind, handler)
  if not kinds[kind] then error("sim.on: unknown event '" .. tostring(kind) .. "'", 2) end
  if type(handler) ~= "function" then error("sim.on(kind, handler): handler is a function", 2) end
  handlers[kind] = handlers[kind] or {}
  insert(handlers[kind], handler)
end
function sim.gate_add(g)
  if type(g) ~= "table" or g.name == nil then
    error("sim.gate_add{name, x1_m, y1_m, x2_m, y2_m}", 2)
  end
  local gate = { name = g.name }
  for _, key in ipairs { "x1_m", "y1_m", "x2_m", "y2_m" } do
    gate[key] = tonumber(g[key])
    if gate[key] == nil then error(format("sim.gate_add: field '%s' is a number", key), 2) end
  end
  insert(gates, gate)
end
local last_cell, touching, last_pose
local function fire(kind, event)
  for _, handler in ipairs(handlers[kind] or {}) do handler(event) end
end
local function dispatch()
  local now = sim.time()
  for _, line in ipairs(host.take_firmware_lines()) do fire("firmware_log", line) end
  for _, restart in ipairs(host.take_firmware_restarts()) do fire("firmware_restart", restart) end
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
        local t0 = ((g.x1_m - last_pose.x_m) * my - (g.y1_m - last_pose.y_m) * mx)
                   / (mx * gy - my * gx)
        if t0 >= 0 and t0 <= 1 then
          -- +1 when crossing from the gate's right side to its left, looking from 1 to 2
          fire("gate_crossed", { name = g.name, direction = after > 0 and 1 or -1, time_s = now })
        end
      end
    end
    last_pose = p
  end
end

-- a table argument takes only the keys its function's signature names: a misspelt key stops the
-- script at its line rather than leaving a default silently in place. Last, so that every
-- function is there, those of this file too.
local check_keys = host.check_keys
for _, name in ipairs(table_taking) do
  local f = sim[name]
  sim[name] = function(...)
    check_keys(name, ...)
    return f(...)
  end
end

-- what the host keeps of the table a scenario file returned, as plain values; read here, where
-- a metamethod's error is a script error like any other
local function inspect(scenario, file)
  if type(scenario) ~= "table" then
    error(file .. ": a scenario file returns sim.scenario { name = ..., run = ... }", 0)
  end
  local stages = { name = scenario.name, params = scenario.params, world = scenario.world,
                   run = scenario.run, finish = scenario.finish, robots = scenario.robots }
  if stages.robots ~= nil and (math.type(stages.robots) ~= "integer" or stages.robots < 1) then
    error(file .. ": the scenario's robots (how many it needs at least) is a whole number, 1 or more", 0)
  end
  if type(stages.name) ~= "string" then
    error(file .. ": the scenario's name is missing or not a string", 0)
  end
  if type(stages.run) ~= "function" then error(file .. ": the scenario has no run function", 0) end
  if stages.finish ~= nil and type(stages.finish) ~= "function" then
    error(file .. ": the scenario's finish is not a function", 0)
  end
  if type(stages.world) ~= "function" then stages.world = nil end
  if stages.params == nil then stages.params = {} end
  if type(stages.params) ~= "table" then
    error(file .. ": the scenario's params is not a table of names and values", 0)
  end
  -- each parameter as { name, type, value as text }
  local described = {}
  for key, value in pairs(stages.params) do
    if type(key) ~= "string" then
      error(format("%s: params has a %s key; parameter names are strings", file, type(key)), 0)
    end
    local ok, text = pcall(tostring, value)
    if not ok then
      local why = type(text) == "string" and text or "(error object is a " .. type(text) .. " value)"
      error(format("%s: parameter '%s' cannot be shown as text: %s", file, key, why), 0)
    end
    described[#described + 1] = { key, type(value), text }
  end
  return stages, described
end

-- the run's parameters: the overrides from --set, checked and typed by the host, in its order;
-- returns the time limit
local function apply(params, overrides)
  for _, override in ipairs(overrides) do params[override[1]] = override[2] end
  return tonumber(params.time_limit_s) or 0
end

return { dispatch = dispatch, inspect = inspect, apply = apply }
