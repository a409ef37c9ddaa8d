-- SPDX-License-Identifier: GPL-3.0-or-later
-- The micromouse contest (dissertation section 5.1.4, with the rules the original did not
-- implement): a maze, 10 minutes in total from the moment the robot first leaves the start
-- cell; a run starts when it leaves the start cell and ends when it enters a goal cell; back in
-- the start cell, the next run may begin; the best run counts. Wall contacts are counted. Every
-- completed run is a record of the list `runs` in result.json: its number, when it started on
-- the contest clock, its time, its path cost (left out when the robot skipped a cell) and the
-- wall contacts during it. A firmware that restarts (reset, watchdog, replug) is treated as the
-- rules treat a mouse its handler touched: the current run ends without a time, the mouse is put
-- back in the start cell, and the contest clock runs on. Each moment the rules act on is an event
-- of the run's recording (sim.event): run_start, wall_contact, goal, back_at_start, restart,
-- contest_end.
return sim.scenario {
  name = "micromouse",
  params = {
    maze = "japan2018",
    maze_class = "auto",   -- classic (180 mm cells), half (90 mm), or auto: half above 16 x 16
    contest_s = 600,       -- the whole contest, from the first departure
    start_within_s = 60,   -- a robot that has not left the start cell by then is out
    max_runs = 0,          -- stop after this many completed runs; 0: use the whole time
    end_on_log = "",       -- stop when the firmware logs exactly this line; "": never
    time_limit_s = 660,    -- start_within_s + contest_s: how long the simulation may run
  },

  world = function(p)
    sim.maze_load(p.maze, { class = p.maze_class })
  end,

  run = function(p)
    local start = sim.maze_get_start()
    -- a run's turn-aware cost (as tables 5.1-5.4 count it): one per cell moved, one per quarter
    -- turn, from the start facing north; nil if the robot skipped a cell
    local function path_cost(cells)
      local hx, hy, cost = 0, 1, 0
      for i = 2, #cells do
        local dx, dy = cells[i].x - cells[i - 1].x, cells[i].y - cells[i - 1].y
        if math.abs(dx) + math.abs(dy) ~= 1 then return nil end
        local turns = (dx == hx and dy == hy) and 0 or (dx == -hx and dy == -hy) and 2 or 1
        cost, hx, hy = cost + turns + 1, dx, dy
      end
      return cost
    end
    local function at_start(c) return c.x == start.x and c.y == start.y end
    local runs, best_s, best_cost = {}, nil, nil
    local cells  -- of the current run, the start cell first
    local contest_from, run_from, may_start = nil, nil, false
    local touching, contacts, run_contacts = false, 0, 0
    local hud_tenth, hud_run  -- what the HUD shows
    local ended_mid_run, firmware_done = false, false
    local restarts, restarted = 0, false
    sim.on("firmware_log", function(line)
      if p.end_on_log ~= "" and line.text == p.end_on_log then firmware_done = true end
    end)
    sim.on("firmware_restart", function() restarted = true end)

    while true do
      if restarted then
        restarted, restarts = false, restarts + 1
        if run_from then
          sim.event("restart", string.format("the firmware restarted: run %d ends without a " ..
                                             "time, the mouse goes back to the start", #runs + 1))
        else
          sim.event("restart", "the firmware restarted: the mouse goes back to the start")
        end
        -- back in the start cell, the next departure is a new run
        run_from, may_start = nil, false
        sim.robot_reset()
      end
      local now, cell = sim.time(), sim.robot_get_cell()
      local touch = sim.robot_is_touching_wall()
      if touch and not touching then
        contacts = contacts + 1
        if run_from then run_contacts = run_contacts + 1 end
        sim.event("wall_contact", string.format("wall contact %d%s", contacts,
                                                run_from and ", in run " .. #runs + 1 or ""))
      end
      touching = touch

      if not contest_from then
        if not at_start(cell) then
          contest_from, run_from, run_contacts = now, now, 0
          cells = { start }
          sim.event("run_start", "the contest starts: run 1")
        elseif now >= p.start_within_s then
          local reason = string.format("never left the start cell in %g s", p.start_within_s)
          sim.event("contest_end", reason)
          sim.fail(reason)
          return
        end
      elseif run_from and sim.maze_is_goal(cell.x, cell.y) then
        runs[#runs + 1] = now - run_from
        cells[#cells + 1] = cell
        local cost = path_cost(cells)
        if not best_s or runs[#runs] < best_s then best_s, best_cost = runs[#runs], cost end
        sim.event("goal", string.format("run %d: %.3f s, path cost %s", #runs, runs[#runs],
                                        cost or "unknown"))
        sim.record_add("runs", { run = #runs, start_s = run_from - contest_from, time_s = runs[#runs],
                                 path_cost = cost, wall_contacts = run_contacts })
        run_from = nil
        if p.max_runs > 0 and #runs >= p.max_runs then break end
      elseif not run_from and at_start(cell) then
        if not may_start then
          sim.event("back_at_start", string.format("back in the start cell: run %d may start",
                                                   #runs + 1))
        end
        may_start = true
      elseif not run_from and may_start and not at_start(cell) then
        run_from, may_start, run_contacts = now, false, 0
        cells = { start }
        sim.event("run_start", string.format("run %d starts", #runs + 1))
      end
      if run_from and cells then
        local last = cells[#cells]
        if cell.x ~= last.x or cell.y ~= last.y then cells[#cells + 1] = cell end
      end
      if contest_from and now - contest_from >= p.contest_s then
        ended_mid_run = run_from ~= nil
        break
      end
      if firmware_done then
        print(string.format("the firmware logged '%s': the contest ends", p.end_on_log))
        if not contest_from then contest_from = now end
        break
      end

      -- the HUD shows tenths of a second: its text is made only when what it shows changes
      local elapsed = contest_from and now - contest_from or 0
      local tenth, run_shown = math.floor(elapsed * 10 + 0.5), #runs + (run_from and 1 or 0)
      if tenth ~= hud_tenth or run_shown ~= hud_run then
        hud_tenth, hud_run = tenth, run_shown
        sim.hud_set(1, string.format("time %6.1f s of %g s", elapsed, p.contest_s))
        sim.hud_set(2, string.format("run %d  best %s", run_shown,
                                     best_s and string.format("%.3f s", best_s) or "-"))
      end
      sim.next_tick()
    end

    -- a time, so a float even when it is the whole contest (an integer parameter)
    local used_s = math.min(sim.time() - contest_from, p.contest_s) + 0.0
    sim.score_set("runs", #runs)
    sim.score_set("time_used_s", used_s)
    sim.score_set("wall_contacts", contacts)
    sim.score_set("firmware_restarts", restarts)
    if best_s then sim.score_set("best_run_s", best_s) end
    if best_cost then sim.score_set("best_run_path_cost", best_cost) end
    local tail = ended_mid_run and string.format("; the time ran out during run %d", #runs + 1) or ""
    local verdict
    if #runs > 0 then
      verdict = string.format("%d run%s, best %.3f s (path cost %s), %.1f s used, %d wall contact%s%s",
                              #runs, #runs == 1 and "" or "s", best_s, best_cost or "unknown",
                              used_s, contacts, contacts == 1 and "" or "s", tail)
    else
      verdict = string.format("no run reached the goal in %.1f s (%d wall contact%s)%s", used_s,
                              contacts, contacts == 1 and "" or "s", tail)
    end
    sim.event("contest_end", verdict)
    if #runs > 0 then sim.pass(verdict) else sim.fail(verdict) end
  end,
}
