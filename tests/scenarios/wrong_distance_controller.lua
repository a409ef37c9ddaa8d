-- SPDX-License-Identifier: GPL-3.0-or-later
-- A wrong controller: algorithm 4 aiming for 0.30 m instead of 0.50 m.
-- The sensor sits 0.048 m left of the centre and looks 45 degrees to the left, so a centre at d
-- from the wall reads (d - 0.048) / cos(45 deg).
local distance_m = 0.30
local goal = (distance_m - 0.048) / math.cos(math.pi / 4)
local base, gain = 500, 900

return function(time_s)
  local reading = sim.signal_get("tof.left_m")
  local error = reading - goal  -- too far from the wall: positive, turn left
  local turn = math.max(-300, math.min(300, gain * error))
  sim.signal_set("left.command", base - turn)
  sim.signal_set("right.command", base + turn)
end
