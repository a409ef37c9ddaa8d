-- SPDX-License-Identifier: GPL-3.0-or-later
-- A controller that floods the run's output: a 4000-character line every step.
local line = string.rep("x", 4000)

return function(time_s)
  print(line)
end
