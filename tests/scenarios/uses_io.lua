-- SPDX-License-Identifier: GPL-3.0-or-later
-- Tries to reach the file system, which the sandbox does not have.
return sim.scenario {
  name = "uses_io",
  run = function()
    local f = io.open("/etc/passwd")
  end,
}
