-- SPDX-License-Identifier: GPL-3.0-or-later
-- A wrong controller: the right speeds, turning clockwise.
return function(time_s)
  sim.signal_set("left.command", 923)
  sim.signal_set("right.command", 762)
end
