-- SPDX-License-Identifier: GPL-3.0-or-later
-- A kidnapped mouse. It explores a maze; the first time after `at_s` that it drives straight
-- through the middle of a cell, it is picked up and put down at rest just as it was in another
-- cell: the nearest cell at least `away` cells off that it has already left in that heading (so
-- the way on is open). It passes when the firmware says it has found its place, names the
-- cell it is really about to enter (next to the robot's), and then reaches a goal cell.
return sim.scenario {
  name = "kidnapped",
  params = { maze = "japan2018", maze_class = "auto", at_s = 30, away = 1, time_limit_s = 300 },

  world = function(p)
    sim.maze_load(p.maze, { class = p.maze_class })
  end,

  run = function(p)
    local heard = {}
    sim.on("firmware_log", function(line) heard[#heard + 1] = line.text end)
    -- the sides the robot has driven through: left[x][y][h] (h 0 north, 1 east, 2 south, 3 west)
    local left, last = {}, sim.robot_get_cell()
    local function watch()
      local cell = sim.robot_get_cell()
      local dx, dy = cell.x - last.x, cell.y - last.y
      if math.abs(dx) + math.abs(dy) == 1 then
        local h = dy == 1 and 0 or dx == 1 and 1 or dy == -1 and 2 or 3
        left[last.x] = left[last.x] or {}
        left[last.x][last.y] = left[last.x][last.y] or {}
        left[last.x][last.y][h] = true
      end
      last = cell
    end
    local cell_m = sim.maze_get_dimensions().cell_m
    -- on a straight through the middle of a cell, along one of the maze's lines
    sim.wait_until(function()
      watch()
      if sim.time() < p.at_s then return false end
      local v, pose = sim.robot_get_velocity(), sim.robot_get_pose()
      local yaw = math.deg(pose.yaw_rad)
      local fx, fy = pose.x_m / cell_m % 1 - 0.5, pose.y_m / cell_m % 1 - 0.5
      return v.v_m_per_s > 0.2 and math.abs(v.omega_rad_per_s) < 0.2 and
             math.abs(yaw - 90 * math.floor(yaw / 90 + 0.5)) < 3 and
             math.abs(fx) < 0.1 and math.abs(fy) < 0.1
    end)
    local here, pose = sim.robot_get_cell(), sim.robot_get_pose()
    local quarter = math.floor(math.deg(pose.yaw_rad) / 90 + 0.5) % 4  -- 0 east, 1 north, ...
    local h = ({ 1, 0, 3, 2 })[quarter + 1]
    local to, best
    for x, column in pairs(left) do
      for y, sides in pairs(column) do
        local d = math.abs(x - here.x) + math.abs(y - here.y)
        if sides[h] and d >= p.away and (not best or d < best or
            (d == best and (y < to.y or (y == to.y and x < to.x)))) then
          to, best = { x = x, y = y }, d
        end
      end
    end
    if not to then
      sim.fail("no cell to put the mouse down in")
      return
    end
    sim.robot_place { x_m = pose.x_m + (to.x - here.x) * cell_m,
                      y_m = pose.y_m + (to.y - here.y) * cell_m, yaw_deg = math.deg(pose.yaw_rad) }
    print(string.format("the mouse is put down in cell (%d, %d), from (%d, %d)", to.x, to.y,
                        here.x, here.y))
    local found
    while true do
      for _, text in ipairs(heard) do
        local x, y = text:match("^found: about to enter cell %((%d+), (%d+)%)")
        if x then
          local cell = sim.robot_get_cell()
          if math.abs(cell.x - x) + math.abs(cell.y - y) ~= 1 then
            sim.fail(string.format("found itself about to enter (%s, %s) in cell (%d, %d)", x, y,
                                   cell.x, cell.y))
            return
          end
          found = text
        elseif (text:match("^lost:") and not text:match("looking")) or text == "done" then
          sim.fail("the firmware said '" .. text .. "'")
          return
        end
      end
      heard = {}
      local cell = sim.robot_get_cell()
      if found and sim.maze_is_goal(cell.x, cell.y) then break end
      sim.next_tick()
    end
    sim.pass(string.format("%s, then the goal at %.3f s", found, sim.time()))
  end,
}
