-- SPDX-License-Identifier: GPL-3.0-or-later
-- Slalom, an example of writing a challenge: posts in a line to the north, passed on the left
-- and the right in turn, without touching one, then over the finish line. It shows boxes, gates,
-- events and parameters; docs/scenarios.md walks through it.
return sim.scenario {
  name = "slalom",
  params = { posts = 4, spacing_m = 0.6, time_limit_s = 30 },

  world = function(p)
    for k = 1, p.posts do
      local y = k * p.spacing_m
      sim.box_add { x_m = 0, y_m = y, size_m = { 0.05, 0.05, 0.10 } }
      -- a gate from the post out to the side it must be passed on: left (west) for odd posts;
      -- gates run west to east, so crossing one northward is direction +1
      if k % 2 == 1 then
        sim.gate_add { name = tostring(k), x1_m = -1, y1_m = y, x2_m = 0, y2_m = y }
      else
        sim.gate_add { name = tostring(k), x1_m = 0, y1_m = y, x2_m = 1, y2_m = y }
      end
    end
    local finish_y = (p.posts + 1) * p.spacing_m
    sim.gate_add { name = "finish", x1_m = -1, y1_m = finish_y, x2_m = 1, y2_m = finish_y }
    sim.robot_place { x_m = 0, y_m = 0, yaw_deg = 90 }
  end,

  run = function(p)
    local next_post, verdict = 1, nil
    sim.on("gate_crossed", function(event)
      if verdict or event.direction < 0 then return end
      if event.name == "finish" then
        if next_post > p.posts then
          verdict = { sim.pass, string.format("through the slalom in %.3f s", event.time_s) }
        else
          verdict = { sim.fail, string.format("finished without passing post %d", next_post) }
        end
      elseif tonumber(event.name) == next_post then
        next_post = next_post + 1
        sim.hud_set(1, string.format("posts passed: %d of %d", next_post - 1, p.posts))
      else
        verdict = { sim.fail, string.format("passed post %d on the wrong side", next_post) }
      end
    end)
    sim.on("wall_contact", function(event)
      verdict = verdict or { sim.fail, string.format("touched a post at %.3f s", event.time_s) }
    end)

    if sim.wait_until(function() return verdict ~= nil end, { timeout_s = p.time_limit_s }) then
      sim.score_set("posts_passed", next_post - 1)
      verdict[1](verdict[2])
    else
      sim.fail(string.format("did not finish in %g s (%d of %d posts)", p.time_limit_s,
                             next_post - 1, p.posts))
    end
  end,
}
