-- SPDX-License-Identifier: GPL-3.0-or-later
-- Passes on the test firmware's greeting, which comes over the link as a log line.
return sim.scenario {
  name = "firmware_hello",
  params = { expect = "test firmware ready" },
  run = function(p)
    local heard
    sim.on("firmware_log", function(line) heard = heard or line end)
    if not sim.wait_until(function() return heard ~= nil end, { timeout_s = 1 }) then
      sim.fail("the firmware said nothing")
    elseif heard.text ~= p.expect then
      sim.fail("the firmware said '" .. heard.text .. "'")
    else
      sim.pass(string.format("heard '%s' at %.3f s", heard.text, heard.time_s))
    end
  end,
}
