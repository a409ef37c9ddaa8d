-- SPDX-License-Identifier: GPL-3.0-or-later
-- Never waits: the instruction budget stops it.
return sim.scenario {
  name = "endless_loop",
  run = function()
    local n = 0
    while true do
      n = n + 1
    end
  end,
}
