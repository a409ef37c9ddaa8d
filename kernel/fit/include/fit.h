// SPDX-License-Identifier: GPL-3.0-or-later
// Fitting a robot file to logs (docs/calibrate.md): simulation error, not equation error. Each
// log's commands are replayed through the robot model (replay.h) and Eigen's Levenberg-Marquardt
// (unsupported/Eigen/LevenbergMarquardt, forward-difference Jacobian) minimises the difference
// between the replayed and the logged wheel speeds. The unknowns are each motor's torque
// constant Kt (= its back-EMF constant, dissertation eq. 3.6) and armature resistance Ra
// (eq. 3.1), as ratios to the file's values.
//
// Identifiability: with the wheel speeds alone, the motor enters the wheel's equation of motion
// (eq. 3.7-3.10, the current of eq. 3.13 with La/Ra far below a step) only through Kt/Ra and
// Kt^2/Ra + lambda, so the viscous damping lambda cannot be told from Kt and Ra; it keeps the
// file's value. A parameter is reported identified when its 95 % confidence interval (from the
// Jacobian at the optimum) is within kIdentifiedWithin of its value; otherwise the file's value
// is kept and the report says so.
//
// The gyro: with the motor constants fitted, a log's gyro_z_rad_s column against the replayed
// robot's true yaw rate w as its imu sees it is the line g = (1 + e) w + b (plugins/imu's model
// about z, cross-axis terms and drift aside), fitted by linear least squares over every row:
// b, the bias, from the standstills, e, the scale error, from the spins.
#ifndef UNIMOUSE_FIT_FIT_H_
#define UNIMOUSE_FIT_FIT_H_

#include <string>
#include <vector>

#include "plugin_registry.h"
#include "replay.h"
#include "residual_plot.h"
#include "robot_spec.h"
#include "sysid_log.h"

namespace unimouse::fit {

/// Largest half-width of a 95 % confidence interval, as a fraction of the value, at which a
/// parameter counts as identified by the logs.
inline constexpr double kIdentifiedWithin = 0.05;
/// A gyro's bias or scale error that is near zero cannot be known within kIdentifiedWithin of
/// itself; it counts as identified when its interval's half-width is within these: 0.01 dps,
/// a few times the ICM-20602's bias instability (0.003 dps), and 0.1 % of the rate.
inline constexpr double kGyroBiasResolution_dps = 0.01;
inline constexpr double kGyroScaleResolution = 0.001;
/// Bounds of a fitted value, as a ratio to the file's: beyond them the log is not of this robot.
inline constexpr double kMinRatio = 0.25, kMaxRatio = 4;
/// Shortest log that can identify anything, seconds.
inline constexpr double kMinLogDuration_s = 2;
/// Smallest largest |command| a log must apply to identify anything.
inline constexpr double kMinCommandSwing = 50;

struct FittedParameter {
  ParameterRef ref;
  double file_value = 0;
  double value = 0;                ///< fitted; the file's when not identified
  double ci_low = 0, ci_high = 0;  ///< 95 % confidence interval of the fitted value
  bool identified = false;
};

/// How close one channel of one log is, before (the file's values) and after the fit.
struct ChannelFit {
  std::string log;
  size_t log_index = 0;  ///< the log's place among those fitted
  std::string channel;
  double r2_before = 0, rmse_before = 0;
  double r2_after = 0, rmse_after = 0;
  /// The channel against time (the log's time at the end of each interval), as logged and as
  /// replayed with the file's and with the fitted values, for the plots.
  std::vector<double> time_s, logged, replayed_before, replayed_after;
};

struct FitReport {
  std::vector<FittedParameter> parameters;
  std::vector<ChannelFit> channels;
  int iterations = 0;
  int replays = 0;  ///< simulations of a whole log
  /// A log has a gyro column and the robot no imu: the column is read and not used.
  bool gyro_not_used = false;
};

/// Checks that a log can identify something on this robot; throws InputError "file:line:
/// reason" for one too short, one whose commands or wheels hardly move, or one whose wheels turn
/// far faster or slower than this robot's encoders and motors can (a log of another robot).
void CheckLogFitsRobot(const SysidLog& log, const RobotSpec& robot, const RobotWiring& wiring);

/// Fits both motors' Kt and Ra to the logs, then, when the logs have a gyro column and the robot
/// an imu, its z gyro's bias (gyro_z_bias_dps) and scale error (gyro_z_scale_error). Each channel's
/// "after" is the replay of the robot with the reported values (the file's where not
/// identified): what the fitted file gives. Deterministic: same inputs, same report.
FitReport FitRobot(const RobotSpec& robot, const PluginRegistry& registry,
                   const std::vector<SysidLog>& logs);

/// r^2 (1 - residual sum of squares / total sum of squares about the mean) and RMSE of a
/// replayed channel against the measured one.
double RSquared(const std::vector<double>& measured, const std::vector<double>& replayed);
double Rmse(const std::vector<double>& measured, const std::vector<double>& replayed);

/// Per channel of a log (the wheels; the gyro when the log has one and the robot an imu): RMSE and
/// largest error of the replay against the log.
struct ChannelComparison {
  std::string channel;
  double rmse = 0, max_error = 0, r2 = 0;
  double max_error_time_s = 0;
  /// The channel against time, as logged and as replayed, for the plots.
  std::vector<double> time_s, logged, replayed;
};
std::vector<ChannelComparison> CompareLog(const RobotSpec& robot, const PluginRegistry& registry,
                                          const SysidLog& log);

/// The plots of a fit's channel: the log, the replay with the file's values and with the fitted
/// ones above; below, the residuals (replayed minus logged) before and after the fit.
Plot FitPlot(const ChannelFit& channel);
/// The plot of a compared channel: the log and the replay above, the residual below.
Plot ComparePlot(const std::string& log, const ChannelComparison& channel);

}  // namespace unimouse::fit

#endif  // UNIMOUSE_FIT_FIT_H_
