-- SPDX-License-Identifier: GPL-3.0-or-later
-- Straight ahead, whatever is in the way.
return function(time_s)
  sim.signal_set("left.command", 450)
  sim.signal_set("right.command", 450)
end
