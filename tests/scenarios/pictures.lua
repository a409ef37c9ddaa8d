-- SPDX-License-Identifier: GPL-3.0-or-later
-- Saves one picture from the run and passes if it was saved, or fails with the reason why not.
return sim.scenario {
  name = "pictures",
  params = { file = "lua/start.png", camera = "chase" },

  world = function(p)
    sim.wall_add { x1_m = -0.2, y1_m = 0.3, x2_m = 0.2, y2_m = 0.3 }
  end,

  run = function(p)
    sim.next_tick()
    local ok, why = sim.snapshot_save(p.file, { camera = p.camera, width = 200, height = 100 })
    if ok then
      sim.pass("saved " .. p.file)
    else
      sim.fail(why)
    end
  end,
}
