// SPDX-License-Identifier: GPL-3.0-or-later
// The IMU on the gyro robot (robots/unimouse-gyro.yaml), against closed forms: the Allan
// deviation of a 10-minute standstill gives back the noise density and the bias instability;
// at rest the accelerometer reads 1 g, in a steady circle v^2/r; the gyro integrated over a
// spin gives the turn times (1 + its scale error); beyond full scale it saturates at the
// register's count; the same seed gives the same readings; wrong parameters are bad input.
#include "imu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "run_program.h"

namespace unimouse {
namespace {

using testing::GyroRobotWith;
using testing::MakeKernel;
using testing::SetSignal;
using testing::SignalValue;

constexpr double kStandardGravity_m_s2 = 9.80665;
constexpr double kRadPerDeg = std::numbers::pi / 180;

// an IMU at the robot's imu site, its truth under "truth", with more parameters
std::string ImuWith(const std::string& params) {
  return "  - { type: unimouse.imu, name: imu,\n"
         "      params: { site: imu, truth_out: truth, " +
         params + " } }\n";
}

// overlapping Allan deviation of samples taken every tau0_s, at averaging time m tau0_s
double AllanDeviation(const std::vector<double>& y, double tau0_s, size_t m) {
  std::vector<long double> theta(y.size() + 1, 0);
  for (size_t i = 0; i < y.size(); ++i) theta[i + 1] = theta[i] + y[i] * tau0_s;
  long double sum = 0;
  size_t count = 0;
  for (size_t k = 0; k + 2 * m < theta.size(); ++k) {
    const long double d = theta[k + 2 * m] - 2 * theta[k + m] + theta[k];
    sum += d * d;
    ++count;
  }
  const double tau_s = static_cast<double>(m) * tau0_s;
  return std::sqrt(static_cast<double>(sum / count) / (2 * tau_s * tau_s));
}

struct AllanFit {
  double noise_density;     // units per sqrt(Hz)
  double bias_instability;  // units
};

// Allan variance of exponentially correlated noise of unit variance at tau = x T (IEEE Std 952,
// annex C, with q_c^2 T / 2 = 1)
double GaussMarkovAllanVariance(double x) {
  return 2 / x * (1 - (3 - 4 * std::exp(-x) + std::exp(-2 * x)) / (2 * x));
}

// fits the closed form of white noise plus a Gauss-Markov drift of known correlation time,
//   AVAR(tau) = N^2 / tau + (B / peak)^2 GMAVAR(tau / T),
// to the measured Allan variance at 40 averaging times from 10 ms to 10 T, each weighted by
// its relative error; the bias instability B is the drift's peak Allan deviation
AllanFit FitAllan(const std::vector<double>& y, double tau0_s, double correlation_s) {
  double peak2 = 0;
  for (double x = 0.5; x < 5; x += 0.001) peak2 = std::max(peak2, GaussMarkovAllanVariance(x));
  double suu = 0, suw = 0, sww = 0, suy = 0, swy = 0;
  for (int k = 0; k < 40; ++k) {
    const double tau_s = 0.01 * std::pow(1000 * correlation_s, k / 39.0);
    const auto m = static_cast<size_t>(std::lround(tau_s / tau0_s));
    const double t = static_cast<double>(m) * tau0_s;
    const double avar = std::pow(AllanDeviation(y, tau0_s, m), 2);
    const double u = 1 / t / avar, w = GaussMarkovAllanVariance(t / correlation_s) / peak2 / avar;
    suu += u * u, suw += u * w, sww += w * w, suy += u, swy += w;
  }
  const double det = suu * sww - suw * suw;
  return {std::sqrt((suy * sww - swy * suw) / det), std::sqrt((swy * suu - suy * suw) / det)};
}

void Drive(Kernel& kernel, double left, double right) {
  SetSignal(kernel, "left.command", left);
  SetSignal(kernel, "right.command", right);
}

// the chassis's heading, radians
double Yaw(const Kernel& kernel) { return kernel.world().RobotPose(kernel.state().data()).yaw_rad; }

TEST(ImuTest, AllanDeviationOfATenMinuteStandstillGivesBackNoiseDensityAndBiasInstability) {
  // white noise and drift of a sensor, nothing else: an ideal chip with these four figures;
  // a correlation time far shorter than a real chip's (minutes), so that ten minutes hold
  // enough of the drift to read its figure within a few percent, and a drift that stands out
  // of the white noise at its peak
  constexpr double kGyroDensity_dps = 0.004, kGyroInstability_dps = 0.01;
  constexpr double kAccelDensity_g = 100e-6, kAccelInstability_g = 200e-6;
  constexpr double kCorrelation_s = 0.2;
  auto kernel = MakeKernel(GyroRobotWith(ImuWith(
      "part: custom, gyro_range_dps: 250, accel_range_g: 2, gyro_noise_dps_per_rt_hz: 0.004, "
      "gyro_bias_instability_dps: 0.01, gyro_bias_tau_s: 0.2, accel_noise_g_per_rt_hz: 100e-6, "
      "accel_bias_instability_g: 200e-6, accel_bias_tau_s: 0.2")));
  for (int i = 0; i < 500; ++i) kernel->Step();  // settle on the wheels
  std::vector<double> gyro, accel;
  const int steps = 600 * 1000;
  gyro.reserve(steps);
  accel.reserve(steps);
  for (int i = 0; i < steps; ++i) {
    kernel->Step();
    gyro.push_back(SignalValue(*kernel, "imu.gyro_z_rad_s") / kRadPerDeg);
    accel.push_back(SignalValue(*kernel, "imu.accel_x_m_s2") / kStandardGravity_m_s2);
  }
  const AllanFit g = FitAllan(gyro, 0.001, kCorrelation_s);
  const AllanFit a = FitAllan(accel, 0.001, kCorrelation_s);
  std::printf("gyro: %.3g dps/sqrt(Hz), %.3g dps; accel: %.3g g/sqrt(Hz), %.3g g\n",
              g.noise_density, g.bias_instability, a.noise_density, a.bias_instability);
  EXPECT_NEAR(g.noise_density, kGyroDensity_dps, 0.10 * kGyroDensity_dps);
  EXPECT_NEAR(g.bias_instability, kGyroInstability_dps, 0.10 * kGyroInstability_dps);
  EXPECT_NEAR(a.noise_density, kAccelDensity_g, 0.10 * kAccelDensity_g);
  EXPECT_NEAR(a.bias_instability, kAccelInstability_g, 0.10 * kAccelInstability_g);
}

TEST(ImuTest, GaussMarkovAllanPeakIsTheKnownConstant) {
  // IEEE Std 952's exponentially correlated noise peaks at 0.437 q_c sqrt(T) near tau = 1.89 T,
  // where its variance is q_c^2 T / 2: 0.437 sqrt(2) = 0.618 standard deviations
  EXPECT_NEAR(plugins::GaussMarkovAllanPeak(), 0.437 * std::sqrt(2.0), 0.002);
}

TEST(ImuTest, AtRestTheAccelerometerReadsOneGUpwards) {
  auto kernel = MakeKernel(GyroRobotWith(ImuWith("part: custom, accel_noise_g_per_rt_hz: 100e-6")));
  for (int i = 0; i < 500; ++i) kernel->Step();
  double x = 0, y = 0, z = 0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    kernel->Step();
    x += SignalValue(*kernel, "imu.accel_x_m_s2") / n;
    y += SignalValue(*kernel, "imu.accel_y_m_s2") / n;
    z += SignalValue(*kernel, "imu.accel_z_m_s2") / n;
  }
  EXPECT_NEAR(z, kStandardGravity_m_s2, 0.02 * kStandardGravity_m_s2);
  EXPECT_NEAR(x, 0, 0.02 * kStandardGravity_m_s2);
  EXPECT_NEAR(y, 0, 0.02 * kStandardGravity_m_s2);
}

TEST(ImuTest, InASteadyCircleTheAccelerometerReadsVSquaredOverR) {
  auto kernel = MakeKernel(GyroRobotWith(ImuWith("part: custom, accel_noise_g_per_rt_hz: 100e-6")));
  const mjModel& m = kernel->mj_model();
  const int site = mj_name2id(&m, mjOBJ_SITE, "imu");
  ASSERT_GE(site, 0);
  // a left turn well inside the grip limit
  Drive(*kernel, 500, 800);
  for (int i = 0; i < 3000; ++i) kernel->Step();
  std::vector<double> px, py, ax, ay;
  std::vector<std::array<double, 9>> frames;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const mjData& d = kernel->state().data();
    kernel->Step();
    px.push_back(d.site_xpos[3 * site]);
    py.push_back(d.site_xpos[3 * site + 1]);
    ax.push_back(SignalValue(*kernel, "imu.accel_x_m_s2"));
    ay.push_back(SignalValue(*kernel, "imu.accel_y_m_s2"));
    std::array<double, 9> frame;
    std::copy(d.site_xmat + 9 * site, d.site_xmat + 9 * site + 9, frame.begin());
    frames.push_back(frame);
  }
  // the circle through the site's path (algebraic least squares, Kasa's method)
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sxz = 0, syz = 0, sz = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    const double x = px[i], y = py[i], z = x * x + y * y;
    sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y, sxz += x * z, syz += y * z, sz += z;
  }
  const double k = static_cast<double>(px.size());
  // normal equations of x^2 + y^2 = a x + b y + c
  const double a11 = sxx, a12 = sxy, a13 = sx, a22 = syy, a23 = sy, a33 = k;
  const double b1 = sxz, b2 = syz, b3 = sz;
  const double det =
      a11 * (a22 * a33 - a23 * a23) - a12 * (a12 * a33 - a23 * a13) + a13 * (a12 * a23 - a22 * a13);
  const double a =
      (b1 * (a22 * a33 - a23 * a23) - a12 * (b2 * a33 - a23 * b3) + a13 * (b2 * a23 - a22 * b3)) /
      det;
  const double b =
      (a11 * (b2 * a33 - a23 * b3) - b1 * (a12 * a33 - a23 * a13) + a13 * (a12 * b3 - b2 * a13)) /
      det;
  const double c =
      (a11 * (a22 * b3 - b2 * a23) - a12 * (a12 * b3 - b2 * a13) + b1 * (a12 * a23 - a22 * a13)) /
      det;
  const double r_m = std::sqrt(c + a * a / 4 + b * b / 4);
  // the speed from the angle swept about the centre: the path's length would count the
  // chassis's jitter on its soft contacts as distance
  double swept_rad = 0;
  for (size_t i = 1; i < px.size(); ++i) {
    const double before = std::atan2(py[i - 1] - b / 2, px[i - 1] - a / 2);
    const double after = std::atan2(py[i] - b / 2, px[i] - a / 2);
    swept_rad += std::remainder(after - before, 2 * std::numbers::pi);
  }
  const double v_m_s = std::abs(swept_rad) / ((n - 1) * 0.001) * r_m;
  ASSERT_GT(std::abs(swept_rad), 2 * std::numbers::pi) << "less than one lap recorded";
  // v^2 / r towards the centre, minus gravity, in the site's axes: the robot slides a little
  // sideways (its x axis is not the path's tangent) and leans on its tyres
  const double centripetal = v_m_s * v_m_s / r_m;
  double measured_x = 0, measured_y = 0, expected_x = 0, expected_y = 0;
  for (size_t i = 0; i < px.size(); ++i) {
    const double to_x = a / 2 - px[i], to_y = b / 2 - py[i], to = std::hypot(to_x, to_y);
    const double f[3] = {centripetal * to_x / to, centripetal * to_y / to, 9.81};
    const std::array<double, 9>& r = frames[i];
    const double share = 1 / static_cast<double>(px.size());
    expected_x += share * (r[0] * f[0] + r[3] * f[1] + r[6] * f[2]);
    expected_y += share * (r[1] * f[0] + r[4] * f[1] + r[7] * f[2]);
    measured_x += share * ax[i];
    measured_y += share * ay[i];
  }
  EXPECT_NEAR(std::hypot(measured_x, measured_y), std::hypot(expected_x, expected_y),
              0.02 * centripetal)
      << "v " << v_m_s << " m/s, r " << r_m << " m";
  EXPECT_NEAR(measured_x, expected_x, 0.02 * centripetal);
  EXPECT_NEAR(measured_y, expected_y, 0.02 * centripetal);
}

TEST(ImuTest, GyroIntegratedOverASpinGivesTheTurnTimesOnePlusItsScaleError) {
  auto kernel = MakeKernel(GyroRobotWith(ImuWith("part: icm20602, gyro_range_dps: 2000")));
  for (int i = 0; i < 200; ++i) kernel->Step();
  // the firmware's calibration: the mean of 400 samples at standstill (KERISE does this)
  double bias_rad_s = 0;
  for (int i = 0; i < 400; ++i) {
    kernel->Step();
    bias_rad_s += SignalValue(*kernel, "imu.gyro_z_rad_s") / 400;
  }
  double integrated_rad = 0, true_rad = 0, yaw = Yaw(*kernel);
  auto step = [&] {
    kernel->Step();
    integrated_rad += (SignalValue(*kernel, "imu.gyro_z_rad_s") - bias_rad_s) * 0.001;
    const double now = Yaw(*kernel);
    true_rad += std::remainder(now - yaw, 2 * std::numbers::pi);
    yaw = now;
  };
  Drive(*kernel, -500, 500);
  while (true_rad < 2 * std::numbers::pi) {
    step();
    ASSERT_LT(kernel->state().data().time, 10) << "the robot did not spin";
  }
  Drive(*kernel, 0, 0);
  for (int i = 0; i < 1000; ++i) step();
  const double scale_error = SignalValue(*kernel, "truth.gyro_scale_error_z");
  EXPECT_NE(scale_error, 0);
  EXPECT_NEAR(integrated_rad / kRadPerDeg, true_rad * (1 + scale_error) / kRadPerDeg, 0.5)
      << "scale error " << scale_error;
}

TEST(ImuTest, ACalibratedZGyroHasItsGivenBiasAndScaleErrorAndTheOtherAxesKeepTheirDraws) {
  // drift off, so that the bias is the turn-on bias alone
  const std::string part = "part: icm20602, gyro_bias_instability_dps: 0";
  auto drawn = MakeKernel(GyroRobotWith(ImuWith(part)));
  auto given = MakeKernel(
      GyroRobotWith(ImuWith(part + ", gyro_z_bias_dps: -0.7, gyro_z_scale_error: 0.025")));
  drawn->Step();
  given->Step();
  EXPECT_NEAR(SignalValue(*given, "truth.gyro_bias_z_rad_s"), -0.7 * kRadPerDeg, 1e-12);
  EXPECT_NEAR(SignalValue(*given, "truth.gyro_scale_error_z"), 0.025, 1e-12);
  EXPECT_NE(SignalValue(*drawn, "truth.gyro_scale_error_z"), 0.025);
  for (const char* axis : {"x", "y"}) {
    EXPECT_EQ(SignalValue(*given, std::string("truth.gyro_bias_") + axis + "_rad_s"),
              SignalValue(*drawn, std::string("truth.gyro_bias_") + axis + "_rad_s"));
    EXPECT_EQ(SignalValue(*given, std::string("truth.gyro_scale_error_") + axis),
              SignalValue(*drawn, std::string("truth.gyro_scale_error_") + axis));
  }
}

TEST(ImuTest, BeyondFullScaleTheGyroSaturatesAtTheRegistersCount) {
  // +-250 dps is 131 LSB/dps on an ICM-20602: full scale is 32750 counts
  auto kernel = MakeKernel(GyroRobotWith(ImuWith("part: icm20602, gyro_range_dps: 250")));
  Drive(*kernel, -800, 800);
  double true_max = 0, counts_max = 0, si_max = 0;
  for (int i = 0; i < 2000; ++i) {
    kernel->Step();
    true_max = std::max(true_max, SignalValue(*kernel, "truth.gyro_z_rad_s"));
    counts_max = std::max(counts_max, SignalValue(*kernel, "imu.gyro_z_counts"));
    si_max = std::max(si_max, SignalValue(*kernel, "imu.gyro_z_rad_s"));
  }
  ASSERT_GT(true_max / kRadPerDeg, 300) << "the spin is too slow to saturate";
  EXPECT_EQ(counts_max, 32750);
  EXPECT_DOUBLE_EQ(si_max / kRadPerDeg, 250);
}

TEST(ImuTest, TheSameSeedGivesTheSameReadingsAndAnotherSeedOthers) {
  auto run = [](uint64_t seed) {
    KernelOptions options;
    options.seed = seed;
    auto kernel = MakeKernel(GyroRobotWith(ImuWith("part: mpu6500")), nullptr, options);
    Drive(*kernel, 300, 700);
    std::vector<double> out;
    for (int i = 0; i < 500; ++i) {
      kernel->Step();
      out.push_back(SignalValue(*kernel, "imu.gyro_z_counts"));
      out.push_back(SignalValue(*kernel, "imu.accel_y_counts"));
    }
    return out;
  };
  EXPECT_EQ(run(7), run(7));
  EXPECT_NE(run(7), run(8));
}

TEST(ImuTest, TheReadingsFollowAFirstOrderLowPassOfTheTrueRate) {
  // a spin cannot start as a step, so the true rate is passed through the first-order filter
  // of bandwidth f_c in closed form (pole exp(-2 pi f_c dt)) and the readings must follow it
  auto kernel = MakeKernel(
      GyroRobotWith(ImuWith("part: custom, dlpf_hz: 20, gyro_range_dps: 2000, odr_hz: 1000")));
  Drive(*kernel, -800, 800);
  const double alpha = 1 - std::exp(-2 * std::numbers::pi * 20 * 0.001);
  double filtered = 0, worst = 0, peak = 0;
  for (int i = 0; i < 300; ++i) {
    kernel->Step();
    filtered += alpha * (SignalValue(*kernel, "truth.gyro_z_rad_s") - filtered);
    worst = std::max(worst, std::abs(SignalValue(*kernel, "imu.gyro_z_rad_s") - filtered));
    peak = std::max(peak, std::abs(filtered));
  }
  ASSERT_GT(peak, 1);
  // within two counts of the closed-form filter
  EXPECT_LT(worst, 2 / (32768 / 2000.0) * kRadPerDeg);
}

class ImuInputTest : public ::testing::Test {
 protected:
  // `unimouse check` on the gyro robot with the IMU given `params`; the IMU's line
  testing::Outcome Check(const std::string& params, int* imu_line) {
    const std::string text =
        GyroRobotWith("  - { type: unimouse.imu, name: imu, params: { " + params + " } }\n");
    *imu_line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    const std::string path = testing::FreshDirectory("imu_input") + "/robot.yaml";
    std::ofstream(path) << text;
    path_ = path;
    return testing::Unimouse("check " + path);
  }
  std::string path_;
};

TEST_F(ImuInputTest, AnUnknownPartIsBadInputAtItsLine) {
  int line = 0;
  const testing::Outcome o = Check("site: imu, part: bmi088", &line);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(path_ + ":" + std::to_string(line) + ":"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("part"), std::string::npos) << o.output;
}

TEST_F(ImuInputTest, ANegativeNoiseFigureIsBadInputAtItsLine) {
  int line = 0;
  const testing::Outcome o = Check("site: imu, gyro_noise_dps_per_rt_hz: -0.004", &line);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(path_ + ":" + std::to_string(line) + ":"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("gyro_noise_dps_per_rt_hz"), std::string::npos) << o.output;
}

TEST_F(ImuInputTest, ASiteThatDoesNotExistIsBadInputAtItsLine) {
  int line = 0;
  const testing::Outcome o = Check("site: imu_on_the_roof", &line);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(path_ + ":" + std::to_string(line) + ":"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("imu_on_the_roof"), std::string::npos) << o.output;
}

TEST_F(ImuInputTest, ARangeThePartDoesNotOfferIsBadInput) {
  int line = 0;
  const testing::Outcome o = Check("site: imu, part: icm20602, gyro_range_dps: 300", &line);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("icm20602 has no full-scale range of +-300 dps"), std::string::npos)
      << o.output;
}

TEST(ImuCheckTest, CheckAcceptsTheGyroRobot) {
  const testing::Outcome o = testing::Unimouse("check unimouse-gyro");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("ok: robot 'unimouse-gyro'"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace unimouse
