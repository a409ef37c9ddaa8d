-- SPDX-License-Identifier: GPL-3.0-or-later
-- Wall distance for robots/unimouse-six.yaml: a proportional-derivative controller on the left
-- sensor that looks straight to the side. It sits 0.048 m left of the centre, so a centre at d
-- from the wall reads d - 0.048 when the robot runs parallel to it; the rate at which the
-- reading changes says how the robot is turned, and damps the approach. A reading is new every
-- 30 ms: the rate is taken between new readings.
local distance_m = 0.50
local goal = distance_m - 0.048
local base, kp, kd = 500, 900, 200
local last, last_s, rate = nil, 0, 0

return function(time_s)
  local reading = sim.signal_get("tof.side_left_m")
  if reading ~= last then
    if last ~= nil and time_s > last_s then rate = (reading - last) / (time_s - last_s) end
    last, last_s = reading, time_s
  end
  local error = reading - goal  -- too far from the wall: positive, turn left
  local turn = math.max(-300, math.min(300, kp * error + kd * rate))
  sim.signal_set("left.command", base - turn)
  sim.signal_set("right.command", base + turn)
end
