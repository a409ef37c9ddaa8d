-- SPDX-License-Identifier: GPL-3.0-or-later
-- Weaves through the slalom from ground truth: heads for waypoints left and right of the posts.
local waypoints = { { -0.3, 0.6 }, { 0.3, 1.2 }, { -0.3, 1.8 }, { 0.3, 2.4 }, { 0.0, 3.3 } }
local next = 1

return function(time_s)
  local pose = sim.robot_get_pose()
  local target = waypoints[math.min(next, #waypoints)]
  local dx, dy = target[1] - pose.x_m, target[2] - pose.y_m
  if dy < 0.05 and next < #waypoints then next = next + 1 end
  local want = math.atan(dy, dx)
  local err = math.atan(math.sin(want - pose.yaw_rad), math.cos(want - pose.yaw_rad))
  local turn = math.max(-350, math.min(350, 700 * err))
  sim.signal_set("left.command", 450 - turn)
  sim.signal_set("right.command", 450 + turn)
end
