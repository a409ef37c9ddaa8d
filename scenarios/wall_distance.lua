-- SPDX-License-Identifier: GPL-3.0-or-later
-- Wall distance (dissertation section 5.1.2): one long wall, its face on x = 0, running north;
-- the robot starts with its centre 10 cm from it, facing north, the wall on its left. Keep the
-- centre within a tolerance of a distance from the wall for a while, moving along it.
return sim.scenario {
  name = "wall_distance",
  params = {
    distance_m = 0.50,        -- from the wall's face to the robot's centre
    tolerance = 0.10,         -- allowed deviation, as a fraction of distance_m
    hold_s = 5,               -- how long without a break
    min_speed_m_per_s = 0.05, -- slower than this is not moving along the wall
    start_m = 0.10,           -- where the robot starts, from the wall
    time_limit_s = 60,
  },

  world = function(p)
    -- 5 cm thick, 25 cm high, 200 m long: far longer than any run
    sim.wall_add { x1_m = -0.025, y1_m = -10, x2_m = -0.025, y2_m = 190,
                   thickness_m = 0.05, height_m = 0.25 }
    sim.robot_place { x_m = p.start_m, y_m = 0, yaw_deg = 90 }
  end,

  run = function(p)
    local held_since, longest_s = nil, 0
    local last = { distance = p.start_m, speed = 0 }
    while sim.time() < p.time_limit_s do
      local pose = sim.robot_get_pose()
      local speed = sim.robot_get_velocity().v_m_per_s
      last.distance, last.speed = pose.x_m, speed
      local near = math.abs(pose.x_m - p.distance_m) <= p.tolerance * p.distance_m
      sim.hud_set(1, string.format("distance %.3f m   goal %.3f m", pose.x_m, p.distance_m))
      if near and speed >= p.min_speed_m_per_s then
        held_since = held_since or sim.time()
        longest_s = math.max(longest_s, sim.time() - held_since)
        if sim.time() - held_since >= p.hold_s then
          sim.score_set("held_s", longest_s)
          sim.pass(string.format("kept %.2f m from the wall within %g %% for %g s",
                                 p.distance_m, p.tolerance * 100, p.hold_s))
          return
        end
      else
        held_since = nil
      end
      sim.next_tick()
    end
    sim.score_set("held_s", longest_s)
    local why
    if math.abs(last.distance - p.distance_m) > p.tolerance * p.distance_m then
      why = string.format("wrong distance: %.3f m from the wall at the end", last.distance)
    elseif last.speed < p.min_speed_m_per_s then
      why = string.format("not moving along the wall (%.3f m/s)", last.speed)
    else
      why = "not steady enough"
    end
    sim.fail(string.format("%s; held at most %.2f s of %g s", why, longest_s, p.hold_s))
  end,
}
