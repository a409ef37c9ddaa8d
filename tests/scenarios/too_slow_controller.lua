-- SPDX-License-Identifier: GPL-3.0-or-later
-- A wrong controller: the right turn, at half the speed.
return function(time_s)
  sim.signal_set("left.command", 350)
  sim.signal_set("right.command", 420)
end
