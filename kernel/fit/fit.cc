// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/LevenbergMarquardt>

#include "unimouse/errors.h"

namespace unimouse::fit {
namespace {

// full scale of the 10-bit sign-magnitude H-bridge (table 4.6)
constexpr double kFullScaleCommand = 1023;
// a log whose wheels turn faster or slower than this factor beyond what the file's motors give
// at the log's commands is of another robot
constexpr double kOtherRobotFactor = 2.5;
// forward-difference step of the Jacobian, relative: sqrt(epsfcn), as in Eigen's NumericalDiff
constexpr double kJacobianEpsfcn = 1e-4;
constexpr int kMaxReplays = 200;

std::string At(const SysidLog& log, size_t row) {
  return log.file + ":" + std::to_string(log.line[row]);
}

// the fit's unknowns: each motor's Kt and Ra as ratios to the file's values
std::vector<ParameterRef> Unknowns(const RobotWiring& w) {
  return {{w.left.motor, "kt_nm_per_a"},
          {w.left.motor, "resistance_ohm"},
          {w.right.motor, "kt_nm_per_a"},
          {w.right.motor, "resistance_ohm"}};
}

struct LogData {
  const SysidLog* log;
  Channels measured;
  std::vector<double> scale;  // each channel's RMS, so that channels weigh alike
};

// the residuals of every log's replay at the ratios x, scaled by each channel's RMS
class ReplayResiduals : public Eigen::DenseFunctor<double> {
 public:
  ReplayResiduals(const RobotSpec& robot, const RobotWiring& wiring, const PluginRegistry& registry,
                  const std::vector<LogData>& logs, const std::vector<ParameterRef>& unknowns,
                  const std::vector<double>& file_values, int residuals, int* replays)
      : Eigen::DenseFunctor<double>(static_cast<int>(unknowns.size()), residuals),
        robot_(robot),
        wiring_(wiring),
        registry_(registry),
        logs_(logs),
        unknowns_(unknowns),
        file_values_(file_values),
        replays_(replays) {}

  // the robot at x. The unknowns come in pairs per motor, (Kt, Ra), searched as the ratios of
  // Kt and of the mechanical time constant's Ra / Kt^2 (eq. 3.1 and 3.7 with La negligible) to
  // the file's: the ramps fix the first (steady speed V / Kt), the steps the second, so the
  // two barely trade off and the search converges in few steps. Ratios beyond the bounds are
  // held at them.
  RobotSpec Robot(const InputType& x) const {
    RobotSpec robot = robot_;
    for (size_t j = 0; j + 1 < unknowns_.size(); j += 2) {
      const auto at = [&](size_t k) {
        return std::clamp(x[static_cast<Eigen::Index>(k)], kMinRatio, kMaxRatio);
      };
      SetParameter(robot, unknowns_[j], file_values_[j] * at(j));
      SetParameter(robot, unknowns_[j + 1], file_values_[j + 1] * at(j + 1) * at(j) * at(j));
    }
    return robot;
  }

  int operator()(const InputType& x, ValueType& f) const {
    Residuals(x, f);
    *replays_ += static_cast<int>(logs_.size());
    return 0;
  }

  // forward differences, as Eigen's NumericalDiff takes them (steps of sqrt(kJacobianEpsfcn)
  // of each ratio), the replays side by side on the machine's cores: each is a simulation of
  // its own, and the numbers are those of one replay after another
  int df(const InputType& x, JacobianType& jacobian) const {
    const Eigen::Index n = x.size();
    const double relative = std::sqrt(kJacobianEpsfcn);
    std::vector<InputType> points(static_cast<size_t>(n + 1), x);
    std::vector<double> h(static_cast<size_t>(n));
    for (Eigen::Index j = 0; j < n; ++j) {
      const size_t at = static_cast<size_t>(j);
      h[at] = x[j] != 0 ? relative * std::abs(x[j]) : relative;
      points[at + 1][j] += h[at];
    }
    const std::vector<ValueType> f = AtEach(points);
    for (Eigen::Index j = 0; j < n; ++j) {
      const size_t at = static_cast<size_t>(j);
      jacobian.col(j) = (f[at + 1] - f[0]) / h[at];
    }
    return 0;
  }

  // the residuals at each point, the replays side by side
  std::vector<ValueType> AtEach(const std::vector<InputType>& points) const {
    std::vector<ValueType> f(points.size(), ValueType(values()));
    std::vector<std::future<void>> replays;
    for (size_t i = 0; i < points.size(); ++i) {
      replays.push_back(std::async(std::launch::async, [&, i] { Residuals(points[i], f[i]); }));
    }
    for (std::future<void>& r : replays) r.get();
    *replays_ += static_cast<int>(points.size() * logs_.size());
    return f;
  }

 private:
  void Residuals(const InputType& x, ValueType& f) const {
    const RobotSpec robot = Robot(x);
    Eigen::Index k = 0;
    for (const LogData& data : logs_) {
      const Channels replayed = ReplayChannels(robot, wiring_, registry_, *data.log);
      for (size_t c = 0; c < replayed.values.size(); ++c) {
        for (size_t i = 0; i < replayed.values[c].size(); ++i) {
          f[k++] = (replayed.values[c][i] - data.measured.values[c][i]) / data.scale[c];
        }
      }
    }
  }

  const RobotSpec& robot_;
  const RobotWiring& wiring_;
  const PluginRegistry& registry_;
  const std::vector<LogData>& logs_;
  const std::vector<ParameterRef>& unknowns_;
  const std::vector<double>& file_values_;
  int* replays_;
};

// Kt of one side from the log's quasi-static rows (the command steady for the last 0.3 s and the
// wheel turning): at steady state with La di/dt = 0 and little load, V = Kt w (eq. 3.1, 3.6)
double SteadyKt(const std::vector<LogData>& data, const RobotWiring::Side& side, bool left) {
  double vw = 0, ww = 0;
  for (const LogData& d : data) {
    const SysidLog& log = *d.log;
    const std::vector<double>& command = left ? log.left_command : log.right_command;
    const std::vector<double>& speed = d.measured.values[left ? 0 : 1];
    size_t steady_since = 0;
    for (size_t i = 1; i < log.rows(); ++i) {
      if (std::abs(command[i] - command[i - 1]) > 2) steady_since = i;
      if (log.time_s[i] - log.time_s[steady_since] < 0.3 || command[i] == 0) continue;
      const double volts = command[i] / kFullScaleCommand * log.battery_v[i];
      const double w = speed[i - 1] / side.counts_per_rad;
      vw += volts * w;
      ww += w * w;
    }
  }
  return ww > 0 ? vw / ww : 0;
}

// the residual variance s^2 of a fit of `unknowns` parameters. Simulation-error residuals are
// correlated from row to row, so they carry less information than their count says: s^2 is
// inflated by (1 + rho) / (1 - rho), rho the lag-one autocorrelation of the residuals (the
// effective sample size of an AR(1) series)
double ResidualVariance(const Eigen::VectorXd& e, Eigen::Index unknowns) {
  double lag1 = 0;
  for (Eigen::Index i = 1; i < e.size(); ++i) lag1 += e[i] * e[i - 1];
  const double rho = std::clamp(lag1 / std::max(e.squaredNorm(), 1e-300), 0.0, 0.99);
  return e.squaredNorm() / std::max<double>(static_cast<double>(e.size() - unknowns), 1) *
         (1 + rho) / (1 - rho);
}

// a linear least-squares fit of y = A theta with the motors' interval: cov = s^2 (A^T A)^-1
struct LinearFit {
  Eigen::VectorXd theta;
  Eigen::MatrixXd covariance;
  bool full_rank = false;
};
LinearFit FitLinear(const Eigen::MatrixXd& a, const Eigen::VectorXd& y) {
  const Eigen::Index n = a.cols();
  const Eigen::MatrixXd information = a.transpose() * a;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(information, Eigen::ComputeFullU | Eigen::ComputeFullV);
  LinearFit fit;
  fit.theta = svd.solve(a.transpose() * y);
  const double s2 = ResidualVariance(y - a * fit.theta, n);
  fit.full_rank = svd.singularValues()(n - 1) > 1e-12 * svd.singularValues()(0);
  fit.covariance = s2 * svd.solve(Eigen::MatrixXd::Identity(n, n));
  return fit;
}

// the z gyro's bias and scale error: the logged rate g against the replayed true yaw rate w is
// g = (1 + e) w + b, a linear least-squares fit over every row of every log with a gyro. Logs
// that never turn the robot cannot pin e: then b alone, at the file's e, from g - (1 + e) w
std::vector<FittedParameter> FitGyro(const RobotSpec& robot, const std::string& imu,
                                     const std::vector<const std::vector<double>*>& logged,
                                     const std::vector<const std::vector<double>*>& yaw_rate) {
  Eigen::Index rows = 0;
  for (const std::vector<double>* g : logged) rows += static_cast<Eigen::Index>(g->size());
  Eigen::MatrixXd a(rows, 2);
  Eigen::VectorXd g(rows);
  Eigen::Index k = 0;
  for (size_t l = 0; l < logged.size(); ++l) {
    for (size_t i = 0; i < logged[l]->size(); ++i, ++k) {
      a(k, 0) = (*yaw_rate[l])[i];
      a(k, 1) = 1;
      g[k] = (*logged[l])[i];
    }
  }
  constexpr double kDegPerRad = 180 / std::numbers::pi;
  const auto parameter = [&](const char* key, double value, double variance, bool full_rank,
                             double resolution, double limit) {
    FittedParameter p;
    p.ref = {imu, key};
    p.file_value = ParameterValue(robot, p.ref);
    const double half = full_rank ? 1.959964 * std::sqrt(std::max(variance, 0.0))
                                  : std::numeric_limits<double>::infinity();
    p.identified = full_rank && std::isfinite(half) && std::isfinite(value) &&
                   half <= std::max(kIdentifiedWithin * std::abs(value), resolution) &&
                   std::abs(value) <= limit;  // limit: the imu's range for the parameter
    p.value = p.identified ? value : p.file_value;
    p.ci_low = value - half;
    p.ci_high = value + half;
    return p;
  };
  const LinearFit both = FitLinear(a, g);
  const FittedParameter scale =
      parameter("gyro_z_scale_error", both.theta[0] - 1, both.covariance(0, 0), both.full_rank,
                kGyroScaleResolution, 0.5);
  FittedParameter bias = parameter("gyro_z_bias_dps", both.theta[1] * kDegPerRad,
                                   both.covariance(1, 1) * kDegPerRad * kDegPerRad, both.full_rank,
                                   kGyroBiasResolution_dps, 1e4);
  if (!scale.identified) {
    const LinearFit alone = FitLinear(a.col(1), g - (1 + scale.value) * a.col(0));
    bias = parameter("gyro_z_bias_dps", alone.theta[0] * kDegPerRad,
                     alone.covariance(0, 0) * kDegPerRad * kDegPerRad, alone.full_rank,
                     kGyroBiasResolution_dps, 1e4);
  }
  return {bias, scale};
}

}  // namespace

double RSquared(const std::vector<double>& measured, const std::vector<double>& replayed) {
  double mean = 0;
  for (double v : measured) mean += v;
  mean /= static_cast<double>(measured.size());
  double residual = 0, total = 0;
  for (size_t i = 0; i < measured.size(); ++i) {
    residual += (measured[i] - replayed[i]) * (measured[i] - replayed[i]);
    total += (measured[i] - mean) * (measured[i] - mean);
  }
  return total > 0 ? 1 - residual / total : 0;
}

double Rmse(const std::vector<double>& measured, const std::vector<double>& replayed) {
  double sum = 0;
  for (size_t i = 0; i < measured.size(); ++i) {
    sum += (measured[i] - replayed[i]) * (measured[i] - replayed[i]);
  }
  return std::sqrt(sum / static_cast<double>(measured.size()));
}

void CheckLogFitsRobot(const SysidLog& log, const RobotSpec& robot, const RobotWiring& wiring) {
  const auto whole = [&](const std::string& reason) { throw InputError(log.file + ": " + reason); };
  if (log.rows() < 3 || log.time_s.back() - log.time_s.front() < kMinLogDuration_s) {
    whole("too short to identify anything: " +
          std::to_string(log.rows() < 1 ? 0 : log.time_s.back() - log.time_s.front()) +
          " s of rows, at least " + std::to_string(kMinLogDuration_s) +
          " s needed (the sysid sequence takes 53 s)");
  }
  double swing = 0;
  for (size_t i = 0; i < log.rows(); ++i) {
    swing = std::max({swing, std::abs(log.left_command[i]), std::abs(log.right_command[i])});
  }
  const Channels measured = MeasuredChannels(log);
  double fastest = 0;
  size_t fastest_row = 0;
  for (const std::vector<double>& channel : measured.values) {
    for (size_t i = 0; i < channel.size(); ++i) {
      if (std::abs(channel[i]) > fastest) {
        fastest = std::abs(channel[i]);
        fastest_row = i + 1;
      }
    }
  }
  if (swing < kMinCommandSwing || fastest == 0) {
    whole("too flat to identify anything: the largest command is " + std::to_string(swing) +
          " and the wheels " + (fastest == 0 ? "never turn" : "hardly turn") +
          " (the sysid sequence ramps, steps and spins the motors)");
  }
  // the fastest the file's motors could turn the wheels at the log's commands: no load, V / Kt
  // (dissertation eq. 3.1 and 3.6 at steady state)
  const double kt_left = ParameterValue(robot, {wiring.left.motor, "kt_nm_per_a"});
  const double kt_right = ParameterValue(robot, {wiring.right.motor, "kt_nm_per_a"});
  double can_reach = 0;
  for (size_t i = 0; i < log.rows(); ++i) {
    // a robot file without a battery: the bridges switch the sketch's 6 V
    const double supply_v = wiring.battery_emf_v > 0 ? log.battery_v[i] : 6.0;
    const auto counts_per_s = [&](double command, double kt, double counts_per_rad) {
      return std::min(std::abs(command), kFullScaleCommand) / kFullScaleCommand * supply_v / kt *
             counts_per_rad;
    };
    can_reach =
        std::max({can_reach, counts_per_s(log.left_command[i], kt_left, wiring.left.counts_per_rad),
                  counts_per_s(log.right_command[i], kt_right, wiring.right.counts_per_rad)});
  }
  if (fastest > kOtherRobotFactor * can_reach || fastest < can_reach / (2 * kOtherRobotFactor)) {
    throw InputError(At(log, fastest_row) + ": the wheels turn " +
                     std::to_string(std::lround(fastest)) + " counts/s where " + robot.file +
                     "'s motors and encoders give at most " +
                     std::to_string(std::lround(can_reach)) +
                     " at these commands: a log of another robot (its counts per turn do not "
                     "fit this file's)");
  }
}

FitReport FitRobot(const RobotSpec& robot, const PluginRegistry& registry,
                   const std::vector<SysidLog>& logs) {
  const RobotWiring wiring = WireRobot(robot);
  std::vector<LogData> data;
  int residuals = 0;
  for (const SysidLog& log : logs) {
    CheckLogFitsRobot(log, robot, wiring);
    LogData d{&log, MeasuredChannels(log), {}};
    for (const std::vector<double>& channel : d.measured.values) {
      double sum = 0;
      for (double v : channel) sum += v * v;
      d.scale.push_back(std::max(std::sqrt(sum / static_cast<double>(channel.size())), 1.0));
      residuals += static_cast<int>(channel.size());
    }
    data.push_back(std::move(d));
  }

  const std::vector<ParameterRef> unknowns = Unknowns(wiring);
  std::vector<double> file_values;
  for (const ParameterRef& p : unknowns) file_values.push_back(ParameterValue(robot, p));

  FitReport report;
  ReplayResiduals residual_fn(robot, wiring, registry, data, unknowns, file_values, residuals,
                              &report.replays);
  Eigen::LevenbergMarquardt<ReplayResiduals> lm(residual_fn);
  lm.setMaxfev(kMaxReplays);
  lm.setXtol(1e-6);
  lm.setFtol(1e-8);
  const Eigen::Index n = static_cast<Eigen::Index>(unknowns.size());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd before(residuals), after(residuals);
  residual_fn(x, before);
  // where the search starts: Kt from the quasi-static rows (steady speed V / Kt, eq. 3.1 and 3.6
  // with no current change), then each motor's time constant ratio as the best
  // of a coarse scan, side by side: the simulation error has local minima (tyre slip in the steps)
  // that a start far off falls into
  const double kt_ratio[] = {SteadyKt(data, wiring.left, true) / file_values[0],
                             SteadyKt(data, wiring.right, false) / file_values[2]};
  Eigen::VectorXd start = x, f(residuals);
  start[0] = std::clamp(kt_ratio[0], kMinRatio, kMaxRatio);
  start[2] = std::clamp(kt_ratio[1], kMinRatio, kMaxRatio);
  residual_fn(start, f);
  double best = f.squaredNorm();
  // one side's time constant after the other's (the two wheels share the chassis), coarse
  // then fine around the best
  for (const std::initializer_list<double> factors :
       {std::initializer_list<double>{0.5, 0.7, 1.4, 2.0},
        std::initializer_list<double>{0.85, 0.92, 1.08, 1.17}}) {
    for (Eigen::Index tau_index : {1, 3}) {
      std::vector<Eigen::VectorXd> trials;
      for (double factor : factors) {
        trials.push_back(start);
        trials.back()[tau_index] = std::clamp(start[tau_index] * factor, kMinRatio, kMaxRatio);
      }
      const std::vector<Eigen::VectorXd> at = residual_fn.AtEach(trials);
      for (size_t i = 0; i < trials.size(); ++i) {
        if (at[i].squaredNorm() < best) {
          best = at[i].squaredNorm();
          start = trials[i];
        }
      }
    }
  }
  // the file's own values, when they replay the logs better than every start found (a log of
  // the very robot): the search then cannot end worse than the file
  if (before.squaredNorm() < best) start = Eigen::VectorXd::Ones(n);
  x = start;
  lm.minimize(x);
  report.iterations = static_cast<int>(lm.iterations());

  // confidence intervals from the Jacobian at the optimum: cov = s^2 (J^T J)^-1
  residual_fn(x, after);
  Eigen::MatrixXd jacobian(residuals, n);
  residual_fn.df(x, jacobian);
  const double s2 = ResidualVariance(after, n);
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(information, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd covariance = s2 * svd.solve(Eigen::MatrixXd::Identity(n, n));
  const bool full_rank = svd.singularValues()(n - 1) > 1e-12 * svd.singularValues()(0);

  // each value and its interval from the searched ratios (Kt = Kt_file x0, Ra = Ra_file x1 x0^2),
  // the interval by the first-order propagation of the covariance
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index kt = j - j % 2;
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
    double ratio = 0;
    if (j == kt) {
      ratio = x[kt];
      gradient[kt] = 1;
    } else {
      ratio = x[j] * x[kt] * x[kt];
      gradient[kt] = 2 * x[j] * x[kt];
      gradient[j] = x[kt] * x[kt];
    }
    FittedParameter p;
    p.ref = unknowns[static_cast<size_t>(j)];
    p.file_value = file_values[static_cast<size_t>(j)];
    const double half = 1.959964 * std::sqrt(std::max(gradient.dot(covariance * gradient), 0.0));
    p.identified = full_rank && std::isfinite(half) && half <= kIdentifiedWithin * ratio &&
                   x[j] > kMinRatio && x[j] < kMaxRatio && x[kt] > kMinRatio && x[kt] < kMaxRatio;
    p.value = p.identified ? p.file_value * ratio : p.file_value;
    p.ci_low = p.file_value * (ratio - half);
    p.ci_high = p.file_value * (ratio + half);
    report.parameters.push_back(p);
  }

  // the robot as the fitted file has it: identified values only, the file's elsewhere
  RobotSpec fitted = robot;
  for (const FittedParameter& p : report.parameters) {
    if (p.identified) SetParameter(fitted, p.ref, p.value);
  }

  std::vector<Channels> was, now;
  for (const LogData& d : data) {
    was.push_back(ReplayChannels(robot, wiring, registry, *d.log));
    now.push_back(ReplayChannels(fitted, wiring, registry, *d.log));
  }
  report.gyro_not_used =
      wiring.imu.empty() && std::any_of(data.begin(), data.end(), [](const LogData& d) {
        return !d.measured.gyro_z_rad_s.empty();
      });
  if (!wiring.imu.empty()) {
    std::vector<const std::vector<double>*> logged, yaw_rate;
    for (size_t l = 0; l < data.size(); ++l) {
      if (now[l].yaw_rate_rad_s.empty()) continue;
      logged.push_back(&data[l].measured.gyro_z_rad_s);
      yaw_rate.push_back(&now[l].yaw_rate_rad_s);
    }
    if (!logged.empty()) {
      for (const FittedParameter& p : FitGyro(robot, wiring.imu, logged, yaw_rate)) {
        report.parameters.push_back(p);
        // one not identified stays out, as in the fitted file: the imu keeps its draw
        if (p.identified) SetParameter(fitted, p.ref, p.value);
      }
      // the gyro's "after" is the fitted file's imu reading
      for (size_t l = 0; l < data.size(); ++l) {
        if (!now[l].yaw_rate_rad_s.empty()) {
          now[l] = ReplayChannels(fitted, wiring, registry, *data[l].log);
        }
      }
    }
  }

  // r^2 and RMSE per log and channel, with the file's values and with the fitted file's
  for (size_t l = 0; l < data.size(); ++l) {
    const LogData& d = data[l];
    const auto add = [&](const std::string& name, const std::vector<double>& measured,
                         const std::vector<double>& with_file,
                         const std::vector<double>& with_fit) {
      ChannelFit cf;
      cf.log = d.log->file;
      cf.log_index = l;
      cf.channel = name;
      cf.r2_before = RSquared(measured, with_file);
      cf.rmse_before = Rmse(measured, with_file);
      cf.r2_after = RSquared(measured, with_fit);
      cf.rmse_after = Rmse(measured, with_fit);
      cf.time_s.assign(d.log->time_s.begin() + 1, d.log->time_s.end());
      cf.logged = measured;
      cf.replayed_before = with_file;
      cf.replayed_after = with_fit;
      report.channels.push_back(cf);
    };
    for (size_t c = 0; c < d.measured.names.size(); ++c) {
      add(d.measured.names[c], d.measured.values[c], was[l].values[c], now[l].values[c]);
    }
    if (!now[l].gyro_z_rad_s.empty()) {
      add(kGyroChannel, d.measured.gyro_z_rad_s, was[l].gyro_z_rad_s, now[l].gyro_z_rad_s);
    }
  }
  return report;
}

std::vector<ChannelComparison> CompareLog(const RobotSpec& robot, const PluginRegistry& registry,
                                          const SysidLog& log) {
  const RobotWiring wiring = WireRobot(robot);
  CheckLogFitsRobot(log, robot, wiring);
  Channels measured = MeasuredChannels(log);
  Channels replayed = ReplayChannels(robot, wiring, registry, log);
  if (!replayed.gyro_z_rad_s.empty()) {
    measured.names.push_back(kGyroChannel);
    measured.values.push_back(measured.gyro_z_rad_s);
    replayed.values.push_back(replayed.gyro_z_rad_s);
  }
  std::vector<ChannelComparison> out;
  for (size_t c = 0; c < measured.names.size(); ++c) {
    ChannelComparison cc;
    cc.channel = measured.names[c];
    cc.rmse = Rmse(measured.values[c], replayed.values[c]);
    cc.r2 = RSquared(measured.values[c], replayed.values[c]);
    for (size_t i = 0; i < measured.values[c].size(); ++i) {
      const double e = std::abs(measured.values[c][i] - replayed.values[c][i]);
      if (e > cc.max_error) {
        cc.max_error = e;
        cc.max_error_time_s = log.time_s[i + 1];
      }
    }
    cc.time_s.assign(log.time_s.begin() + 1, log.time_s.end());
    cc.logged = measured.values[c];
    cc.replayed = replayed.values[c];
    out.push_back(cc);
  }
  return out;
}

namespace {

std::vector<double> Difference(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  return d;
}

}  // namespace

Plot FitPlot(const ChannelFit& c) {
  Plot plot;
  plot.title = std::filesystem::path(c.log).filename().string() + ": " + c.channel +
               "; logged (black), replayed with the file's values " +
               "(orange) and the fitted ones (blue)";
  plot.time_s = c.time_s;
  plot.panels.push_back({c.channel,
                         {{c.logged, kLoggedColour},
                          {c.replayed_before, kFileColour},
                          {c.replayed_after, kFittedColour}}});
  plot.panels.push_back({"residual: replayed - logged",
                         {{Difference(c.replayed_before, c.logged), kFileColour},
                          {Difference(c.replayed_after, c.logged), kFittedColour}}});
  return plot;
}

Plot ComparePlot(const std::string& log, const ChannelComparison& c) {
  Plot plot;
  plot.title = std::filesystem::path(log).filename().string() + ": " + c.channel +
               "; logged (black), simulated (blue)";
  plot.time_s = c.time_s;
  plot.panels.push_back({c.channel, {{c.logged, kLoggedColour}, {c.replayed, kFittedColour}}});
  plot.panels.push_back(
      {"residual: simulated - logged", {{Difference(c.replayed, c.logged), kFittedColour}}});
  return plot;
}

}  // namespace unimouse::fit
