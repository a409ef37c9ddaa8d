-- SPDX-License-Identifier: GPL-3.0-or-later
-- Tries to outlast the instruction budget by catching its error, again and again.
return sim.scenario {
  name = "swallow_budget",
  run = function()
    while true do
      pcall(function() while true do end end)
    end
  end,
}
