-- SPDX-License-Identifier: GPL-3.0-or-later
-- A wrong mouse for the micromouse rules: it leaves the start cell, which starts the contest,
-- then goes back and forth between two cells of the first column, never reaching a goal cell.
-- Like scripted_mouse.lua, it jumps from cell to cell: { time_s, x, y }.
local timeline = { { 0.0, 0, 0 }, { 1.0, 0, 1 }, { 2.0, 0, 2 } }
local period_s = 2.0  -- after the timeline: (0, 1) and (0, 2) in turn, a second each
local at = nil

local function cell_at(time_s)
  local cell = timeline[1]
  for _, entry in ipairs(timeline) do
    if entry[1] <= time_s + 1e-9 then cell = entry end
  end
  if time_s >= timeline[#timeline][1] then
    local phase = (time_s - timeline[#timeline][1]) % period_s
    cell = phase < period_s / 2 and timeline[#timeline] or timeline[#timeline - 1]
  end
  return cell
end

return function(time_s)
  local cell = cell_at(time_s)
  if cell ~= at then
    at = cell
    sim.robot_place { x_m = 0.09 + 0.18 * cell[2], y_m = 0.09 + 0.18 * cell[3], yaw_deg = 90 }
  end
end
