// SPDX-License-Identifier: GPL-3.0-or-later
// A robot's system-identification log: the CSV the sysid sketch (arduino-lib/examples/sysid)
// writes, or a lab's own firmware writes in the same columns (docs/calibrate.md).
#ifndef UNIMOUSE_FIT_SYSID_LOG_H_
#define UNIMOUSE_FIT_SYSID_LOG_H_

#include <string>
#include <vector>

namespace unimouse::fit {

/// The columns a log must have, in any order; more columns are ignored.
inline constexpr const char* kRequiredColumns[] = {"time_s",    "left_command", "right_command",
                                                   "battery_v", "left_counts",  "right_counts"};
/// The optional column of an IMU's yaw rate, rad/s counter-clockwise positive.
inline constexpr const char* kGyroColumn = "gyro_z_rad_s";
/// Most rows a log may have: an hour at 100 rows a second.
inline constexpr size_t kMaxLogRows = 360'000;

struct SysidLog {
  std::string file;
  /// One entry per row: seconds since the sequence started, strictly increasing.
  std::vector<double> time_s;
  /// The H-bridge commands applied from this row until the next, -1023..1023.
  std::vector<double> left_command, right_command;
  /// The supply the H-bridges switch, volts.
  std::vector<double> battery_v;
  /// Encoder counts since the start, read at the row's time.
  std::vector<double> left_counts, right_counts;
  /// The IMU's yaw rate at the row's time; empty when the log has no gyro column.
  std::vector<double> gyro_z_rad_s;
  /// The CSV line of each row (the header is line 1), for errors.
  std::vector<int> line;

  size_t rows() const { return time_s.size(); }
};

/// Reads a log; throws InputError "file:line: reason" for a missing column, a value that is not
/// a finite number, time that does not increase, or a file too large.
SysidLog ReadSysidLog(const std::string& path);

}  // namespace unimouse::fit

#endif  // UNIMOUSE_FIT_SYSID_LOG_H_
