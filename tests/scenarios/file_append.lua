-- SPDX-License-Identifier: GPL-3.0-or-later
-- Writes two lines to a file of the run's output directory, then tries the name `name`: passes
-- when the file is written and fails with the script error for a name outside the directory.
return sim.scenario {
  name = "file_append",
  params = { name = "" },
  run = function(p)
    assert(sim.file_append("lines.csv", "a,b\n"))
    assert(sim.file_append("lines.csv", "1,2\n"))
    if p.name ~= "" then sim.file_append(p.name, "x\n") end
    sim.pass("written")
  end,
}
