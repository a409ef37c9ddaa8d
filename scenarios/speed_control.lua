-- SPDX-License-Identifier: GPL-3.0-or-later
-- Speed control (dissertation section 5.1.1): on an open floor, hold a linear speed and an
-- angular speed, counter-clockwise positive, both within a tolerance and both at once, for a
-- while. Every number is a parameter: unimouse run --scenario speed_control --set hold_s=3
return sim.scenario {
  name = "speed_control",
  params = {
    speed_m_per_s = 1.0,   -- linear speed to hold
    turn_rad_per_s = 2.0,  -- angular speed to hold, counter-clockwise positive
    tolerance = 0.10,      -- allowed deviation, as a fraction of each target
    hold_s = 5,            -- how long both must hold without a break
    time_limit_s = 60,
  },

  world = function(p)
    sim.robot_place { x_m = 0, y_m = 0, yaw_deg = 90 }
  end,

  run = function(p)
    local function within(value, target)
      return math.abs(value - target) <= p.tolerance * math.abs(target)
    end
    local held_since, longest_s = nil, 0
    local sum_v, sum_w, samples = 0, 0, 0  -- the last second, for the reason
    while sim.time() < p.time_limit_s do
      local velocity = sim.robot_get_velocity()
      local v, w = velocity.v_m_per_s, velocity.omega_rad_per_s
      sim.hud_set(1, string.format("linear %6.3f m/s   goal %.2f", v, p.speed_m_per_s))
      sim.hud_set(2, string.format("angular %6.3f rad/s goal %.2f", w, p.turn_rad_per_s))
      if within(v, p.speed_m_per_s) and within(w, p.turn_rad_per_s) then
        held_since = held_since or sim.time()
        longest_s = math.max(longest_s, sim.time() - held_since)
        if sim.time() - held_since >= p.hold_s then
          sim.score_set("held_s", longest_s)
          sim.pass(string.format("held %.2f m/s and %.2f rad/s within %g %% for %g s",
                                 p.speed_m_per_s, p.turn_rad_per_s, p.tolerance * 100, p.hold_s))
          return
        end
      else
        held_since = nil
      end
      if sim.time() > p.time_limit_s - 1 then
        sum_v, sum_w, samples = sum_v + v, sum_w + w, samples + 1
      end
      sim.next_tick()
    end

    -- say what was wrong, from the last second's averages
    local v, w = sum_v / math.max(samples, 1), sum_w / math.max(samples, 1)
    local what = {}
    if w * p.turn_rad_per_s < 0 then what[#what + 1] = "turning the wrong way" end
    if math.abs(v) < p.speed_m_per_s * (1 - p.tolerance) then what[#what + 1] = "too slow" end
    if math.abs(v) > p.speed_m_per_s * (1 + p.tolerance) then what[#what + 1] = "too fast" end
    if not within(w, p.turn_rad_per_s) and w * p.turn_rad_per_s >= 0 then
      what[#what + 1] = "turning at the wrong rate"
    end
    sim.score_set("held_s", longest_s)
    sim.fail(string.format("%s: %.3f m/s and %.3f rad/s at the end, held at most %.2f s of %g s",
                           #what > 0 and table.concat(what, ", ") or "not steady enough",
                           v, w, longest_s, p.hold_s))
  end,
}
