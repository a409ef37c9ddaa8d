-- SPDX-License-Identifier: GPL-3.0-or-later
-- Passes with three of the run's seeded random numbers as its reason; no os, no load.
return sim.scenario {
  name = "random_numbers",
  params = { label = "draws", enabled = true },
  run = function(p)
    assert(os == nil and load == nil and dofile == nil and require == nil, "sandbox leak")
    sim.wait(0.01)
    sim.pass(string.format("%s %s %d %.6f %d", p.label, tostring(p.enabled), math.random(100),
                           math.random(), math.random(5, 9)))
  end,
}
