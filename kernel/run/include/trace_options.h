// SPDX-License-Identifier: GPL-3.0-or-later
// The run's trace on demand: the rate and the channels of the robot file's trace loggers
// (unimouse.logger), or no trace at all, from the command line or a batch manifest.
#ifndef UNIMOUSE_RUN_TRACE_OPTIONS_H_
#define UNIMOUSE_RUN_TRACE_OPTIONS_H_

#include <string>

#include "robot_spec.h"

namespace unimouse {

/// What a run asks of its trace.
struct TraceOptions {
  double period_s = -1;  ///< seconds between rows; 0 for no trace, -1 for the robot file's
  std::string signals;   ///< comma-separated signals it records; "" for the robot file's
};

/// Applies `trace` to every unimouse.logger of `robot`: removes them for period 0, else sets
/// their period and signals where given. Throws InputError for a negative or non-finite period.
void ApplyTraceOptions(const TraceOptions& trace, RobotSpec& robot);

}  // namespace unimouse

#endif  // UNIMOUSE_RUN_TRACE_OPTIONS_H_
