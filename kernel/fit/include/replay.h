// SPDX-License-Identifier: GPL-3.0-or-later
// A log's commands replayed through the robot file's own model (its world, components and
// physics; DESIGN.md "Fitting is simulation"), and the channels it measured beside the ones
// the replay gives.
#ifndef UNIMOUSE_FIT_REPLAY_H_
#define UNIMOUSE_FIT_REPLAY_H_

#include <string>
#include <vector>

#include "plugin_registry.h"
#include "robot_spec.h"
#include "sysid_log.h"

namespace unimouse::fit {

/// How a robot file is wired for a log: the inputs the commands go to, the encoder of each
/// side and the motor that drives that wheel.
struct RobotWiring {
  struct Side {
    std::string command_input;  ///< the robot's input the side's command goes to
    std::string joint;          ///< the wheel hinge the side's encoder reads
    double counts_per_rad = 0;  ///< encoder counts per radian of the wheel (gear x cpr / 2 pi)
    std::string motor;          ///< the unimouse.dc_motor component on that wheel
  };
  Side left, right;
  /// The battery's open-circuit voltage in the file; 0 when it has no unimouse.battery.
  double battery_emf_v = 0;
  /// The first unimouse.imu component and the signal of its z gyro in rad/s; empty when the
  /// file has none.
  std::string imu, imu_gyro_z;
};

/// Finds the wiring of a robot file: inputs left.command and right.command, an encoder writing
/// left.encoder_counts and right.encoder_counts, a dc_motor on each encoder's wheel. Throws
/// InputError naming the file for a robot that lacks one.
RobotWiring WireRobot(const RobotSpec& robot);

/// A component parameter of the robot file: a dc_motor's constant or the imu's z gyro's bias
/// and scale error.
struct ParameterRef {
  std::string component;
  std::string key;
};
/// Returns a parameter's value in the robot file (the model's default when the file leaves it
/// out; 0 for an imu's gyro_z_bias_dps and gyro_z_scale_error, which the imu then draws within
/// its tolerances); throws InputError when the component does not exist.
double ParameterValue(const RobotSpec& robot, const ParameterRef& parameter);
/// Whether the robot file leaves the parameter to a draw each run: an imu's gyro_z_bias_dps or
/// gyro_z_scale_error that the file does not give.
bool ParameterDrawn(const RobotSpec& robot, const ParameterRef& parameter);
/// Sets a parameter's value in the robot spec, as if the file gave it.
void SetParameter(RobotSpec& robot, const ParameterRef& parameter, double value);

/// Measured or replayed channels at a log's rows: each wheel's speed in counts per second over
/// the interval that ends at a row (so rows 1..n-1).
struct Channels {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  ///< one vector per name
  /// The IMU's yaw rate at rows 1..n-1, rad/s counter-clockwise: as logged, or as the replayed
  /// robot's imu reads it. Empty when the log has no gyro column or the robot no imu.
  std::vector<double> gyro_z_rad_s;
  /// The true yaw rate the replayed robot's imu saw, through its low-pass filter, at the same
  /// rows (replays only): its reading without its errors, noise and rounding.
  std::vector<double> yaw_rate_rad_s;
};
/// The name of the gyro's channel in reports and plots.
inline constexpr const char* kGyroChannel = "gyro_z_rad_s";
Channels MeasuredChannels(const SysidLog& log);

/// Replays a log on the robot: each row's commands from its time until the next row's, scaled by
/// the row's battery voltage over the file's, on an open floor, seed 1, without the robot's
/// loggers, links and range sensors (which write files, wait for firmware, or do not matter).
/// The encoders are read before their quantisation (the wheel's angle times counts per radian,
/// less the part of a count the encoder is expected to hold back), so that the replay is smooth
/// in the parameters. With a gyro column and an imu, also the imu's
/// z reading and the site's true yaw rate at each row.
Channels ReplayChannels(const RobotSpec& robot, const RobotWiring& wiring,
                        const PluginRegistry& registry, const SysidLog& log);

}  // namespace unimouse::fit

#endif  // UNIMOUSE_FIT_REPLAY_H_
