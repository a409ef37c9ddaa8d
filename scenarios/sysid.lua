-- SPDX-License-Identifier: GPL-3.0-or-later
-- System identification (docs/calibrate.md): an open floor for the sysid example's test pattern
-- (arduino-lib/examples/sysid). Every CSV line the firmware logs goes to `log_file` in the run's
-- output directory, for `unimouse fit` and `unimouse compare`; the run passes when the firmware
-- logs `sysid done` and fails when the sequence has not ended within the time limit.
--   unimouse run --scenario sysid --link native:sysid --out out/sysid
return sim.scenario {
  name = "sysid",
  params = {
    log_file = "sysid.csv",  -- in the run's output directory
    time_limit_s = 70,       -- the sequence takes about 53 s
  },

  world = function(p)
    sim.robot_place { x_m = 0, y_m = 0, yaw_deg = 90 }
  end,

  run = function(p)
    local lines, done, refused = 0, false, nil
    sim.on("firmware_log", function(event)
      local text = event.text
      if text == "sysid done" then
        done = true
      elseif text:match("^time_s,") or text:match("^[%d%-]") then
        local ok, why = sim.file_append(p.log_file, text .. "\n")
        if ok then lines = lines + 1 else refused = refused or why end
      end
    end)
    while sim.time() < p.time_limit_s and not done and not refused do
      sim.next_tick()
    end
    sim.score_set("log_lines", lines)
    if refused then
      sim.fail("could not write " .. p.log_file .. ": " .. refused)
    elseif done then
      sim.pass(string.format("%d lines in %s", lines, p.log_file))
    else
      sim.fail(string.format("the firmware did not log 'sysid done' within %g s (%d lines)",
                             p.time_limit_s, lines))
    end
  end,
}
