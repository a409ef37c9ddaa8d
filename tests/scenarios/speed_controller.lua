-- SPDX-License-Identifier: GPL-3.0-or-later
-- A controller for the speed_control scenario, as firmware would do it: wheel speeds from the
-- encoder counts, each wheel driven to its target by feedforward plus an integral term.
-- Targets: v = (vr + vl) / 2 and w = (vr - vl) / (2 d) (eq. 3.26, 3.28) solved for the wheels.
local v, w = 1.0, 2.0
local half_track_m, wheel_m, counts_per_turn = 0.048, 0.016, 358.32
local kt, supply_v = 0.079025, 6.0
local target = { left = (v - w * half_track_m) / wheel_m, right = (v + w * half_track_m) / wheel_m }
local integral = { left = 0, right = 0 }
local counts = { left = 0, right = 0 }
local last_s = 0

return function(time_s)
  for _, side in ipairs { "left", "right" } do
    counts[side] = counts[side] + sim.signal_get(side .. ".encoder_counts")
  end
  if time_s - last_s < 0.01 - 1e-9 then return end
  for _, side in ipairs { "left", "right" } do
    local speed = counts[side] / counts_per_turn * 2 * math.pi / (time_s - last_s)
    integral[side] = integral[side] + (target[side] - speed) * (time_s - last_s)
    local volts = target[side] * kt + 0.05 * integral[side]
    sim.signal_set(side .. ".command", math.max(-1023, math.min(1023, volts / supply_v * 1023)))
    counts[side] = 0
  end
  last_s = time_s
end
