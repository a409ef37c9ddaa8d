-- SPDX-License-Identifier: GPL-3.0-or-later
-- A test opponent in the race: from the north-east corner (15, 15) of a 16 x 16 maze it jumps a
-- cell every 0.1 s, west along row 15 to (8, 15), then south down column 8 to the goal cell
-- (8, 8). It places its own robot (sim.robot_place without a robot's name), so it enters the
-- goal at 14 x 0.1 = 1.4 s: 7 cells west, 7 south.
local cells = {}
for x = 15, 8, -1 do cells[#cells + 1] = { x, 15 } end
for y = 14, 8, -1 do cells[#cells + 1] = { 8, y } end
local at = 0

return function(time_s)
  local step = math.min(#cells, math.floor(time_s / 0.1 + 1e-9) + 1)
  if step ~= at then
    at = step
    sim.robot_place { x_m = 0.09 + 0.18 * cells[step][1], y_m = 0.09 + 0.18 * cells[step][2],
                      yaw_deg = -90 }
  end
end
