-- SPDX-License-Identifier: GPL-3.0-or-later
return sim.scenario {
  name = "syntax_error",
  run = function()
    if then
  end,
}
