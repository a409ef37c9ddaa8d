-- SPDX-License-Identifier: GPL-3.0-or-later
-- A race: two to four mice in one maze, each from its own corner, first to a goal cell wins.
--
-- Robot 1 starts in the maze's start cell facing north; robot 2 in the opposite corner facing
-- south, robot 3 in the south-east corner facing west, robot 4 in the north-west corner facing
-- east (`--start` moves a robot elsewhere). Each corner is made a start cell as the rules make
-- the first one: a wall on the mouse's right. Seen from its own corner every mouse then stands
-- where a firmware written for the contest expects to, and in a square maze with a goal in the
-- centre every corner is as far from the goal.
--
-- A robot's race time is when its centre first enters a goal cell, plus `contact_penalty_s` for
-- each time it touched another robot. The race ends when every robot has arrived or at the time
-- limit; the lowest race time wins. Every robot is a record of the list `robots`.
-- what the race has seen so far, by robot name; run() fills it, decide() reads it
local arrived, contacts = {}, {}

-- the results: a record per robot, its scores, the winner; passed when a robot arrived
local function decide(p)
  local winner, best
  for i, name in ipairs(sim.robots()) do
    local n = contacts[name] or 0
    local record = { robot = name, robot_contacts = n }
    sim.score_set("robot" .. i .. "_robot_contacts", n)
    if arrived[name] then
      local t = arrived[name] + p.contact_penalty_s * n
      record.arrived_s, record.race_time_s = arrived[name], t
      sim.score_set("robot" .. i .. "_race_time_s", t)
      if best == nil or t < best then winner, best = name, t end
    end
    sim.record_add("robots", record)
  end
  if winner then
    sim.score_set("winning_time_s", best)
    sim.pass(string.format("%s wins in %.3f s", winner, best))
  else
    sim.fail("no robot reached the goal")
  end
end

return sim.scenario {
  name = "race",
  robots = 2,
  params = {
    maze = "japan2018",
    contact_penalty_s = 3,  -- added to a robot's time for each contact with another robot
    time_limit_s = 300,
  },

  world = function(p)
    sim.maze_load(p.maze)
    local m = sim.maze_get_dimensions()
    local w, h, c = m.width, m.height, m.cell_m
    -- each corner's cell and heading (yaw, degrees)
    local corners = { { 0, 0, 90 }, { w - 1, h - 1, -90 }, { w - 1, 0, 180 }, { 0, h - 1, 0 } }
    -- the side of the wall on the mouse's right, by its heading
    local right = { [90] = { 1, 0 }, [-90] = { -1, 0 }, [180] = { 0, 1 }, [0] = { 0, -1 } }
    for i, name in ipairs(sim.robots()) do
      local k = corners[i]
      if k == nil then break end
      local x, y = (k[1] + 0.5) * c, (k[2] + 0.5) * c
      if i > 1 then sim.robot_place { x_m = x, y_m = y, yaw_deg = k[3], robot = name } end
      local r = right[k[3]]
      local cx, cy = x + r[1] * c / 2, y + r[2] * c / 2
      local ax, ay = r[2] * c / 2, r[1] * c / 2
      sim.wall_add { x1_m = cx - ax, y1_m = cy - ay, x2_m = cx + ax, y2_m = cy + ay }
    end
  end,

  run = function(p)
    local names, touching = sim.robots(), {}
    for _, name in ipairs(names) do contacts[name] = 0 end
    while true do
      local waiting = 0
      for _, name in ipairs(names) do
        local other = sim.robot_touching_robot(name)
        if other and not touching[name] then contacts[name] = contacts[name] + 1 end
        touching[name] = other
        local cell = sim.robot_get_cell(name)
        if not arrived[name] and sim.maze_is_goal(cell.x, cell.y) then
          arrived[name] = sim.time()
          print(string.format("%s reached the goal at %.3f s", name, sim.time()))
        end
        if not arrived[name] then waiting = waiting + 1 end
      end
      sim.hud_set(1, string.format("race %.1f s", sim.time()))
      if waiting == 0 then return decide(p) end
      sim.next_tick()
    end
  end,

  -- out of time: the robots that arrived are ranked; none arrived is a failed race
  finish = function(p, ended)
    if ended.status == "running" then decide(p) end
  end,
}
