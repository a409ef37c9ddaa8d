// SPDX-License-Identifier: GPL-3.0-or-later
#include "trace_options.h"

#include <algorithm>
#include <cmath>

#include "unimouse/errors.h"

namespace unimouse {

void ApplyTraceOptions(const TraceOptions& trace, RobotSpec& robot) {
  UNIMOUSE_THROW_UNLESS(std::isfinite(trace.period_s) && trace.period_s >= -1,
                        "--trace-period must be 0 (no trace) or a positive number of seconds");
  auto is_logger = [](const ComponentSpec& c) { return c.type == "unimouse.logger"; };
  if (trace.period_s == 0) {
    std::erase_if(robot.components, is_logger);
    return;
  }
  for (ComponentSpec& c : robot.components) {
    if (!is_logger(c)) continue;
    if (trace.period_s > 0) c.period_s = trace.period_s;
    if (trace.signals.empty()) continue;
    // the signals given replace the robot file's, and are checked as its own would be
    const std::string where = "--trace-signals " + trace.signals;
    c.params.kind = YamlNode::Kind::kMap;
    std::erase_if(c.params.entries, [](const auto& e) { return e.first.scalar == "signals"; });
    YamlNode key, value;
    key.kind = value.kind = YamlNode::Kind::kScalar;
    key.scalar = "signals";
    value.scalar = trace.signals;
    key.location = value.location = {where, 0, 0};
    c.params.entries.emplace_back(std::move(key), std::move(value));
  }
}

}  // namespace unimouse
