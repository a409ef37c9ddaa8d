-- SPDX-License-Identifier: GPL-3.0-or-later
-- Drives round the time-trial track from ground truth: steer towards the tangent of the lane's
-- centre line (radius 1.9 m), corrected for the distance from it. `direction` 1 is
-- counter-clockwise; the tests make a copy with -1 to go the wrong way.
local direction = 1
local base, turn_gain, lane_gain = 500, 600, 1.5
local from_y, to_y, lane_r = -3.237, -0.737, 1.9

local function desired_heading(x, y)
  if y > from_y and y < to_y then
    -- on a straight: north on the east side, south on the west side (counter-clockwise)
    local outward = math.abs(x) - lane_r
    local tangent = x > 0 and math.pi / 2 or -math.pi / 2
    if direction < 0 then tangent = tangent + math.pi end
    return tangent + direction * lane_gain * outward
  end
  local cy = y >= to_y and to_y or from_y
  local phi = math.atan(y - cy, x)
  local outward = math.sqrt(x * x + (y - cy) ^ 2) - lane_r
  return phi + direction * math.pi / 2 + direction * lane_gain * outward
end

return function(time_s)
  local pose = sim.robot_get_pose()
  local want = desired_heading(pose.x_m, pose.y_m)
  local err = math.atan(math.sin(want - pose.yaw_rad), math.cos(want - pose.yaw_rad))
  local turn = math.max(-400, math.min(400, turn_gain * err))
  sim.signal_set("left.command", base - turn)
  sim.signal_set("right.command", base + turn)
end
