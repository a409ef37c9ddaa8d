-- SPDX-License-Identifier: GPL-3.0-or-later
-- Fails at t = 0.5 s on a nil value, in a helper that run calls.
local function x_of(pose)
  return pose.x_m
end
return sim.scenario {
  name = "runtime_error",
  params = { delay_s = 0.5 },
  run = function(p)
    sim.wait(p.delay_s)
    local x = x_of(nil)
    return x
  end,
}
