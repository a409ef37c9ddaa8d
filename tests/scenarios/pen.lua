-- SPDX-License-Identifier: GPL-3.0-or-later
-- The world-building helpers at work: a pen of straight walls (a polyline) closed by a half
-- circle of radius 0.3 m to the north (an arc). The robot drives north into the arc, and once it
-- touches, it is reset to its start.
return sim.scenario {
  name = "pen",
  params = { pen = true },

  world = function(p)
    if p.pen then
      sim.wall_polyline { points = { { 0.3, 0 }, { 0.3, -0.3 }, { -0.3, -0.3 }, { -0.3, 0 } } }
      sim.wall_arc { cx_m = 0, cy_m = 0, radius_m = 0.3, from_deg = 0, to_deg = 180 }
    end
    sim.robot_place { x_m = 0, y_m = -0.1, yaw_deg = 90 }
  end,

  run = function(p)
    local touched
    sim.on("wall_contact", function() touched = touched or sim.robot_get_pose() end)
    sim.signal_set("left.command", 500)
    sim.signal_set("right.command", 500)
    if not sim.wait_until(function() return touched ~= nil end, { timeout_s = 3 }) then
      sim.fail("drove 3 s without touching a wall")
      return
    end
    sim.signal_set("left.command", 0)
    sim.signal_set("right.command", 0)
    sim.robot_reset()
    sim.next_tick()
    local back = sim.robot_get_pose()
    sim.pass(string.format("touched at y=%.3f; reset to x=%.3f y=%.3f", touched.y_m, back.x_m,
                           back.y_m))
  end,
}
