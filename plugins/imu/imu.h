// SPDX-License-Identifier: GPL-3.0-or-later
// A MEMS 3-axis gyro and 3-axis accelerometer at a robot site (the dissertation's first item of
// future work, chapter 6). Each physics step it takes the site's true angular velocity and
// specific force from MuJoCo, passes them through the part's errors and filters, and at the
// output data rate writes what the chip's data registers would hold, as raw counts and in SI
// units:
//
//   y = (I + S + C) x + b0 + b(t) + w        per sensor, in the site's frame
//   f <- f + a (y - f),  a = 1 - exp(-2 pi f_c dt)        first-order DLPF at f_c
//   counts = clamp(round(clamp(f, -FS, FS) * sensitivity), -32768, 32767)   every 1/ODR
//
// S (scale-factor errors) and C (cross-axis sensitivities) are diagonal and off-diagonal
// matrices drawn once per run, b0 the turn-on bias, all uniform within the part's +- tolerance;
// b(t) is a first-order Gauss-Markov drift whose Allan deviation peaks at the bias instability;
// w is white noise of the part's noise density. A robot file can fix the z gyro's b0 and S
// (gyro_z_bias_dps, gyro_z_scale_error: a chip calibrated by `unimouse fit`). Every draw comes from
// streams named after the component, so a seed gives the same readings bit for bit.
#ifndef UNIMOUSE_PLUGINS_IMU_H_
#define UNIMOUSE_PLUGINS_IMU_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

/// The figures of one IMU part at one selected range, in the units its datasheet uses.
struct ImuFigures {
  double gyro_range_dps;
  double gyro_sensitivity_lsb_per_dps;
  double gyro_noise_dps_per_rt_hz;
  double gyro_bias_dps;
  double gyro_bias_instability_dps;
  double gyro_bias_tau_s;
  double gyro_scale_error;
  double gyro_cross_axis;
  double accel_range_g;
  double accel_sensitivity_lsb_per_g;
  double accel_noise_g_per_rt_hz;
  double accel_bias_g;
  double accel_bias_instability_g;
  double accel_bias_tau_s;
  double accel_scale_error;
  double accel_cross_axis;
  double odr_hz;
  double dlpf_hz;
};

/// Returns the gyro sensitivity of `part` at full-scale range `range_dps`, LSB per dps; throws
/// InputError for a range the part does not offer. `custom` takes any range at 32768 / range.
double GyroSensitivity(const std::string& part, double range_dps);
/// Returns the accelerometer sensitivity of `part` at `range_g`, LSB per g; as GyroSensitivity.
double AccelSensitivity(const std::string& part, double range_g);
/// Returns the figures of a named part at its default ranges (2000 dps, 4 g); `custom` is an
/// ideal chip (no noise, bias or errors). Throws InputError for an unknown name.
ImuFigures ImuPart(const std::string& part);

/// Returns the largest Allan deviation of a first-order Gauss-Markov process of unit standard
/// deviation: about 0.617, at an averaging time of about 1.89 correlation times.
double GaussMarkovAllanPeak();

struct ImuParams {
  std::string site;
  std::string part = "icm20602";
  std::string out;
  std::string truth_out;
  double gyro_range_dps = 2000;
  double gyro_sensitivity_lsb_per_dps = 16.4;
  double gyro_noise_dps_per_rt_hz = 0.004;
  double gyro_bias_dps = 1;
  double gyro_bias_instability_dps = 0.003;
  double gyro_bias_tau_s = 100;
  double gyro_scale_error = 0.01;
  double gyro_cross_axis = 0.02;
  double gyro_z_bias_dps = 0;
  double gyro_z_scale_error = 0;
  double accel_range_g = 4;
  double accel_sensitivity_lsb_per_g = 8192;
  double accel_noise_g_per_rt_hz = 100e-6;
  double accel_bias_g = 0.025;
  double accel_bias_instability_g = 50e-6;
  double accel_bias_tau_s = 100;
  double accel_scale_error = 0.01;
  double accel_cross_axis = 0.02;
  double odr_hz = 1000;
  double dlpf_hz = 250;
  param::GivenSet given;

  template <class V>
  void Visit(V& v) {
    using param::NonNegative;
    using param::Positive;
    v("site", site, "MuJoCo site the chip sits at; its axes are the chip's x, y, z",
      param::Required{});
    v("part", part, "part whose datasheet figures are the defaults; custom: an ideal chip",
      param::OneOf{"mpu6500|icm20602|lsm6ds3|custom"});
    v("out", out, "prefix of the signals it writes; empty: the component's name");
    v("truth_out", truth_out,
      "prefix of the true rates, specific forces, drawn errors and biases it also writes; "
      "empty: none");
    v("gyro_range_dps", gyro_range_dps, "gyro full-scale range; readings saturate there",
      Positive{});
    v("gyro_sensitivity_lsb_per_dps", gyro_sensitivity_lsb_per_dps,
      "gyro register counts per dps at that range", Positive{});
    v("gyro_noise_dps_per_rt_hz", gyro_noise_dps_per_rt_hz, "gyro rate noise density",
      NonNegative{});
    v("gyro_bias_dps", gyro_bias_dps, "gyro turn-on bias tolerance (+-), drawn per axis",
      NonNegative{});
    v("gyro_bias_instability_dps", gyro_bias_instability_dps,
      "gyro bias instability: peak Allan deviation of the Gauss-Markov drift", NonNegative{});
    v("gyro_bias_tau_s", gyro_bias_tau_s, "correlation time of the gyro's bias drift", Positive{});
    v("gyro_scale_error", gyro_scale_error,
      "gyro sensitivity tolerance (+-, a fraction), drawn per axis", NonNegative{});
    v("gyro_cross_axis", gyro_cross_axis,
      "gyro cross-axis sensitivity tolerance (+-, a fraction), drawn per pair", NonNegative{});
    v("gyro_z_bias_dps", gyro_z_bias_dps,
      "the z axis's turn-on bias, signed, instead of a draw (a calibrated chip: unimouse fit)",
      param::Range{-1e4, 1e4});
    v("gyro_z_scale_error", gyro_z_scale_error,
      "the z axis's scale-factor error, signed fraction, instead of a draw (a calibrated chip)",
      param::Range{-0.5, 0.5});
    v("accel_range_g", accel_range_g, "accelerometer full-scale range; readings saturate there",
      Positive{});
    v("accel_sensitivity_lsb_per_g", accel_sensitivity_lsb_per_g,
      "accelerometer register counts per g at that range", Positive{});
    v("accel_noise_g_per_rt_hz", accel_noise_g_per_rt_hz, "accelerometer noise density",
      NonNegative{});
    v("accel_bias_g", accel_bias_g, "accelerometer zero-g offset tolerance (+-), drawn per axis",
      NonNegative{});
    v("accel_bias_instability_g", accel_bias_instability_g,
      "accelerometer bias instability: peak Allan deviation of the Gauss-Markov drift",
      NonNegative{});
    v("accel_bias_tau_s", accel_bias_tau_s, "correlation time of the accelerometer's bias drift",
      Positive{});
    v("accel_scale_error", accel_scale_error,
      "accelerometer sensitivity tolerance (+-, a fraction), drawn per axis", NonNegative{});
    v("accel_cross_axis", accel_cross_axis,
      "accelerometer cross-axis sensitivity tolerance (+-, a fraction), drawn per pair",
      NonNegative{});
    v("odr_hz", odr_hz, "output data rate: how often the data registers change", Positive{});
    v("dlpf_hz", dlpf_hz, "bandwidth (-3 dB) of the digital low-pass filter", Positive{});
  }
};

class Imu final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.imu";
  static constexpr const char* kSummary =
      "MEMS gyro and accelerometer: bias, drift, scale and cross-axis errors, noise, DLPF, ODR, "
      "saturation, 16-bit counts";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = ImuParams;

  explicit Imu(Params params);
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;

  /// Returns the figures in force: the part's, with what the robot file gave.
  const ImuFigures& figures() const { return f_; }

 private:
  // one of the two sensors, in SI units (rad/s or m/s^2)
  struct Channel {
    double range = 0;            // full scale
    double counts_per_unit = 0;  // sensitivity
    double noise_sd = 0;         // white noise per internal step
    double bias = 0;             // turn-on tolerance
    double drift_sd = 0;         // stationary sd of the Gauss-Markov drift
    double drift_decay = 0;      // exp(-dt / tau)
    double drift_step_sd = 0;    // its innovation each step: drift_sd sqrt(1 - decay^2)
    double scale_error = 0;
    double cross_axis = 0;
    SignalId si[3], counts[3], truth[3], truth_scale[3], truth_bias[3];
    RngId draws, noise, drift;
  };

  void DrawErrors(const ResetContext& ctx, const Channel& c, double* slots) const;
  void Update(const SenseContext& ctx, const Channel& c, const double truth[3], double* slots,
              bool sample) const;
  void SiteMotion(const mjModel& m, const mjData& d, const double* previous_v, double out_omega[3],
                  double out_force[3], double out_v[3]) const;

  const Params p_;
  ImuFigures f_;
  Channel gyro_, accel_;
  int site_ = -1;
  int body_ = -1;
  double dt_s_ = 0;
  double dlpf_alpha_ = 1;
  double sample_period_s_ = 0;
  bool truth_ = false;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_IMU_H_
