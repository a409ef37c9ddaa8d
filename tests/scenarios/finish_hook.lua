-- SPDX-License-Identifier: GPL-3.0-or-later
-- The finish stage: called once the run is over, it sees how the run ended, adds a score and
-- decides a run that ran out of time undecided.
return sim.scenario {
  name = "finish_hook",
  params = { decide_in_run = false, time_limit_s = 1 },
  run = function(p)
    if p.decide_in_run then
      sim.wait(0.25)
      sim.pass("decided in run")
    else
      sim.wait(100)
    end
  end,
  finish = function(p, ended)
    sim.score_set("finished_at_s", ended.time_s)
    sim.score_set("was_decided", ended.status == "running" and 0 or 1)
    sim.pass("decided in finish")  -- only takes effect when run did not decide
  end,
}
