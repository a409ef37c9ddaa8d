-- SPDX-License-Identifier: GPL-3.0-or-later
-- Wall distance for robots/unimouse-skid.yaml: algorithm 4's proportional controller on the left
-- 45-degree sensor (tests/scenarios/wall_controller.lua), with a larger turn allowed: a
-- skid-steer robot turns by dragging its wheels sideways, so the same difference between its
-- sides turns it less than the two-wheeled robot.
local distance_m = 0.50
local goal = (distance_m - 0.048) / math.cos(math.pi / 4)
local base, gain, most = 500, 1400, 450

return function(time_s)
  local reading = sim.signal_get("tof.left_m")
  local error = reading - goal  -- too far from the wall: positive, turn left
  local turn = math.max(-most, math.min(most, gain * error))
  sim.signal_set("left.command", base - turn)
  sim.signal_set("right.command", base + turn)
end
