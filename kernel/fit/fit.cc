// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <filesystem>
#include <future>
#include <initializer_list>
#include <limits>
#include <memory>
#include <mutex>
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
// replayed points kept for the search to come back to (a few MB for a minute's log)
constexpr size_t kRecentReplays = 16;
// searches on the counts at most, each from a better point of a scan around the last one's end
constexpr int kSearchRounds = 4;
// a command that changes by more than this from one row to the next is a step (the ramps change
// theirs by under one a row)
constexpr double kStep = 2;

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

// The segment of each row 1..n-1 of a log: a new one begins after each step of either command.
std::vector<int> StepSegments(const SysidLog& log) {
  std::vector<int> segment;
  int current = 0;
  for (size_t i = 1; i < log.rows(); ++i) {
    const size_t from = i - 1;
    if (from > 0 && (std::abs(log.left_command[from] - log.left_command[from - 1]) > kStep ||
                     std::abs(log.right_command[from] - log.right_command[from - 1]) > kStep)) {
      ++current;
    }
    segment.push_back(current);
  }
  return segment;
}

// Each wheel's counts since the last step of either command, at rows 1..n-1, from its speeds
// between rows. A speed from two rounded counts carries the difference of two roundings, so its
// errors are correlated from row to row, where a count's rounding is its own; and a step's lag
// (the time constant times the speed it reaches) stays in the counts until the next step, where
// in the speeds it shows in the first rows alone: the counts pin the time constant, and so Ra.
std::vector<std::vector<double>> CountsSinceStep(const SysidLog& log,
                                                 const std::vector<int>& segments,
                                                 const std::vector<std::vector<double>>& speeds) {
  std::vector<std::vector<double>> counts(speeds.size());
  for (size_t c = 0; c < speeds.size(); ++c) {
    double since = 0;
    for (size_t k = 0; k < segments.size(); ++k) {
      if (k > 0 && segments[k] != segments[k - 1]) since = 0;
      since += speeds[c][k] * (log.time_s[k + 1] - log.time_s[k]);
      counts[c].push_back(since);
    }
  }
  return counts;
}

// a channel's RMS, at least 1, so that channels weigh alike
double Rms(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  return std::max(std::sqrt(sum / static_cast<double>(values.size())), 1.0);
}

struct LogData {
  const SysidLog* log;
  Channels measured;
  std::vector<int> segments;                // StepSegments
  std::vector<std::vector<double>> counts;  // CountsSinceStep of the measured speeds
  std::vector<double> speed_scale, counts_scale;
};

// what the search compares: the wheels' speeds between rows, or their counts since each step
enum class Compared { kSpeeds, kCountsSinceStep };

// the residuals of every log's replay at the ratios x, of speeds or of counts since each step,
// each channel scaled by its RMS
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

  void Compare(Compared compared) { compared_ = compared; }

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
    return 0;
  }

  // forward differences, as Eigen's NumericalDiff takes them (steps of sqrt(kJacobianEpsfcn)
  // of each ratio; of Kt a tenth of that on the counts, whose drift over a long step is Kt's
  // error times the step's counts), the replays side by side on the machine's cores: each is a
  // simulation of its own, and the numbers are those of one replay after another
  int df(const InputType& x, JacobianType& jacobian) const {
    const Eigen::Index n = x.size();
    std::vector<InputType> points(static_cast<size_t>(n + 1), x);
    std::vector<double> h(static_cast<size_t>(n));
    for (Eigen::Index j = 0; j < n; ++j) {
      const double relative = compared_ == Compared::kCountsSinceStep && j % 2 == 0
                                  ? std::sqrt(kJacobianEpsfcn) / 10
                                  : std::sqrt(kJacobianEpsfcn);
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
    return f;
  }

  // the trials replayed side by side; `point` moves to the best that beats `best` (its squared
  // residuals), if any
  void MoveToBest(const std::vector<InputType>& trials, InputType& point, double& best) const {
    const std::vector<ValueType> at = AtEach(trials);
    for (size_t i = 0; i < trials.size(); ++i) {
      if (at[i].squaredNorm() < best) {
        best = at[i].squaredNorm();
        point = trials[i];
      }
    }
  }

 private:
  // every log replayed at x. The search comes back to points it has replayed (the Jacobian's
  // base is the last step's end, a scan's best is the next search's start, the speeds and the
  // counts come from one replay), so the last few are kept
  std::shared_ptr<const std::vector<Channels>> Replayed(const InputType& x) const {
    {
      std::lock_guard<std::mutex> lock(recent_mutex_);
      for (const auto& [at, channels] : recent_) {
        if (at == x) return channels;
      }
    }
    const RobotSpec robot = Robot(x);
    auto channels = std::make_shared<std::vector<Channels>>();
    for (const LogData& data : logs_) {
      channels->push_back(ReplayChannels(robot, wiring_, registry_, *data.log));
    }
    std::lock_guard<std::mutex> lock(recent_mutex_);
    *replays_ += static_cast<int>(logs_.size());
    recent_.emplace_back(x, channels);
    if (recent_.size() > kRecentReplays) recent_.pop_front();
    return channels;
  }

  void Residuals(const InputType& x, ValueType& f) const {
    const std::shared_ptr<const std::vector<Channels>> replayed_logs = Replayed(x);
    Eigen::Index k = 0;
    const bool counts = compared_ == Compared::kCountsSinceStep;
    for (size_t l = 0; l < logs_.size(); ++l) {
      const LogData& data = logs_[l];
      const std::vector<std::vector<double>>& speeds = (*replayed_logs)[l].values;
      const std::vector<std::vector<double>> replayed =
          counts ? CountsSinceStep(*data.log, data.segments, speeds) : speeds;
      const std::vector<std::vector<double>>& logged = counts ? data.counts : data.measured.values;
      for (size_t c = 0; c < replayed.size(); ++c) {
        const double scale = counts ? data.counts_scale[c] : data.speed_scale[c];
        for (size_t i = 0; i < replayed[c].size(); ++i) {
          f[k++] = (replayed[c][i] - logged[c][i]) / scale;
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
  Compared compared_ = Compared::kSpeeds;
  mutable std::mutex recent_mutex_;
  mutable std::deque<std::pair<InputType, std::shared_ptr<const std::vector<Channels>>>> recent_;
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
      if (std::abs(command[i] - command[i - 1]) > kStep) steady_since = i;
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
    LogData d{&log, MeasuredChannels(log), StepSegments(log), {}, {}, {}};
    d.counts = CountsSinceStep(log, d.segments, d.measured.values);
    for (size_t c = 0; c < d.counts.size(); ++c) {
      d.speed_scale.push_back(Rms(d.measured.values[c]));
      d.counts_scale.push_back(Rms(d.counts[c]));
      residuals += static_cast<int>(d.counts[c].size());
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
  const Eigen::Index n = static_cast<Eigen::Index>(unknowns.size());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd before(residuals);
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
      residual_fn.MoveToBest(trials, start, best);
    }
  }
  // the file's own values, when they replay the logs better than every start found (a log of
  // the very robot): the search then cannot end worse than the file
  if (before.squaredNorm() < best) start = Eigen::VectorXd::Ones(n);
  x = start;
  // then the search on the counts since each step, which pin the time constants where the
  // speeds hardly do. Their error is rough (tyre slip in the steps), so each end of the search is
  // tried against a scan around it, and searched again from a better point
  residual_fn.Compare(Compared::kCountsSinceStep);
  lm.setXtol(1e-4);
  lm.setFtol(1e-5);
  for (int round = 0; round < kSearchRounds; ++round) {
    lm.minimize(x);
    report.iterations += static_cast<int>(lm.iterations());
    double best_here = lm.fnorm() * lm.fnorm();
    const Eigen::VectorXd was = x;
    // each time constant alone by 3 and by 12 % (the dips tyre slip makes are some percent
    // wide; a strong motor's steps slip most), and both the opposite ways by 3 %: the wheels
    // share the chassis, so one too long and the other too short is a valley of its own. Kt
    // needs no scan: the search's own steps of it are fine enough
    struct Direction {
      std::array<double, 4> exponents;
      double step;
    };
    for (const Direction& d : {Direction{{0, 1, 0, 0}, 0.03}, Direction{{0, 0, 0, 1}, 0.03},
                               Direction{{0, 1, 0, -1}, 0.03}, Direction{{0, 1, 0, 0}, 0.12},
                               Direction{{0, 0, 0, 1}, 0.12}}) {
      std::vector<Eigen::VectorXd> trials;
      for (double sign : {-1, 1}) {
        trials.push_back(x);
        for (Eigen::Index j = 0; j < n; ++j) {
          const double factor = std::pow(1 + sign * d.step, d.exponents[j]);
          trials.back()[j] = std::clamp(x[j] * factor, kMinRatio, kMaxRatio);
        }
      }
      residual_fn.MoveToBest(trials, x, best_here);
    }
    if (x == was) break;
  }

  // Confidence intervals from the counts' Jacobian at the optimum, by the cluster-robust
  // (sandwich) covariance cov = A^-1 (sum_g J_g^T r_g r_g^T J_g) A^-1 G / (G - 1), A = J^T J,
  // g each log's segments between steps: a count since a step carries every error of the rows
  // before it, so residuals are correlated within a segment and independent across. They say
  // how far the residuals' spread moves the fit, not how far a model error (tyre slip) pulls it:
  // they are narrower than the errors seen (docs/calibrate.md, limits)
  Eigen::VectorXd after(residuals);
  residual_fn(x, after);
  Eigen::MatrixXd jacobian(residuals, n);
  residual_fn.df(x, jacobian);
  std::vector<Eigen::VectorXd> scores;
  Eigen::Index k = 0;
  for (const LogData& d : data) {
    const size_t first = scores.size();
    scores.resize(first + static_cast<size_t>(d.segments.back() + 1), Eigen::VectorXd::Zero(n));
    for (size_t c = 0; c < d.counts.size(); ++c) {
      for (int segment : d.segments) {
        scores[first + static_cast<size_t>(segment)] += jacobian.row(k).transpose() * after[k];
        ++k;
      }
    }
  }
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(n, n);
  for (const Eigen::VectorXd& g : scores) meat += g * g.transpose();
  const double clusters = static_cast<double>(scores.size());
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(information, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd inverse = svd.solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::MatrixXd covariance =
      inverse * meat * inverse * clusters / std::max(clusters - 1, 1.0);
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
