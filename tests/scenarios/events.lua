-- SPDX-License-Identifier: GPL-3.0-or-later
-- Marks moments of the run with sim.event at times of its own choosing: two at 0.25 s, one about
-- the first robot at 0.75 s, one with a 1,500-byte text at 1 s; with flood = N, N more at
-- 1.25 s, half of them, and at 1.5 s, the rest, to meet the bound on events.
return sim.scenario {
  name = "events",
  params = { flood = 0 },
  run = function(p)
    sim.wait(0.25)
    sim.event("first", "a quarter of a second in")
    sim.event("first", "at the same moment")
    sim.wait(0.5)
    sim.event("about_robot_1", "three quarters of a second in", sim.robots()[1])
    sim.wait(0.25)
    sim.event("long", string.rep("x", 1500))
    sim.wait(0.25)
    local half = p.flood // 2
    for i = 1, half do sim.event("flood", "flood " .. i) end
    sim.wait(0.25)
    for i = half + 1, p.flood do sim.event("flood", "flood " .. i) end
    sim.pass("marked")
  end,
}
