-- SPDX-License-Identifier: GPL-3.0-or-later
-- Time trial (dissertation section 5.1.3) on the original simulator's stadium track: a lane
-- 0.8 m wide between walls 0.2 m thick and 0.15 m high, two 2.5 m straights joined by half
-- circles (inner wall radius 1.3-1.5 m, outer 2.3-2.5 m), driven counter-clockwise. A lap
-- counts when the robot crosses the finish line across the east straight northward, having
-- crossed the checkpoint across the west straight southward since: only whole laps in the right
-- direction. The first crossing starts the clock. (The original's arc centres sat 13-27 mm off
-- the straights' ends; here they meet them.)
local straight_from, straight_to = -3.237, -0.737  -- y range of the straights
local line_y = (straight_from + straight_to) / 2   -- finish line and checkpoint

return sim.scenario {
  name = "time_trial",
  params = { laps = 3, time_limit_s = 180 },

  world = function(p)
    local function wall(x1, y1, x2, y2)
      sim.wall_add { x1_m = x1, y1_m = y1, x2_m = x2, y2_m = y2, thickness_m = 0.2, height_m = 0.15 }
    end
    for _, x in ipairs { -2.4, -1.4, 1.4, 2.4 } do wall(x, straight_from, x, straight_to) end
    -- each half circle as 25 straight pieces of 7.2 degrees
    for _, arc in ipairs { { y = straight_to, from = 0 }, { y = straight_from, from = 180 } } do
      for _, r in ipairs { 1.4, 2.4 } do
        sim.wall_arc { cx_m = 0, cy_m = arc.y, radius_m = r, from_deg = arc.from,
                       to_deg = arc.from + 180, segments = 25, thickness_m = 0.2, height_m = 0.15 }
      end
    end
    sim.robot_place { x_m = 1.921, y_m = -3.054, yaw_deg = 90 }
  end,

  run = function(p)
    local laps, best_s, lap_from = {}, nil, nil
    local armed = false
    local last = sim.robot_get_pose()
    while sim.time() < p.time_limit_s do
      local pose = sim.robot_get_pose()
      local east = pose.x_m > 1.5 and pose.x_m < 2.3
      local west = pose.x_m < -1.5 and pose.x_m > -2.3
      if west and last.y_m >= line_y and pose.y_m < line_y then armed = true end
      if (east and last.y_m > line_y and pose.y_m <= line_y) or
         (west and last.y_m < line_y and pose.y_m >= line_y) then
        sim.fail("wrong direction: the track runs counter-clockwise")
        return
      end
      if east and last.y_m < line_y and pose.y_m >= line_y then
        if lap_from and armed then
          laps[#laps + 1] = sim.time() - lap_from
          best_s = math.min(best_s or math.huge, laps[#laps])
          print(string.format("lap %d: %.3f s", #laps, laps[#laps]))
        end
        if not lap_from or armed then lap_from, armed = sim.time(), false end
        if #laps >= p.laps then
          for i, t in ipairs(laps) do sim.score_set("lap_" .. i .. "_s", t) end
          sim.score_set("best_lap_s", best_s)
          sim.pass(string.format("%d laps, best %.3f s", #laps, best_s))
          return
        end
      end
      sim.hud_set(1, string.format("lap %d of %d   best %s", #laps + 1, p.laps,
                                   best_s and string.format("%.3f s", best_s) or "-"))
      last = pose
      sim.next_tick()
    end
    if best_s then sim.score_set("best_lap_s", best_s) end
    sim.fail(string.format("%d of %d laps in %g s", #laps, p.laps, p.time_limit_s))
  end,
}
