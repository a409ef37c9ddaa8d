-- SPDX-License-Identifier: GPL-3.0-or-later
-- Returns a table whose every field lookup fails: loading it is a script error, not a crash.
return setmetatable({}, {
  __index = function(_, key)
    error("there is no " .. key)
  end,
})
