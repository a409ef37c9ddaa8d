// SPDX-License-Identifier: GPL-3.0-or-later
#include "imu.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <tuple>

namespace unimouse::plugins {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180;
constexpr double kStandardGravity_m_s2 = 9.80665;

// state slots of one channel: error matrix (I + S + C), turn-on bias, drift, filter
constexpr int kMatrix = 0;
constexpr int kTurnOn = 9;
constexpr int kDrift = 12;
constexpr int kFilter = 15;
constexpr int kChannelSize = 18;
// then the site's previous world velocity and the time of the next output sample
constexpr int kGyro = 0;
constexpr int kAccel = kChannelSize;
constexpr int kPreviousV = 2 * kChannelSize;
constexpr int kNextSample = kPreviousV + 3;
constexpr int kStateSize = kNextSample + 1;

constexpr const char* kAxes[3] = {"x", "y", "z"};

bool Near(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

// the full-scale steps a part offers, with their sensitivities
struct Step {
  double range;
  double lsb_per_unit;
};

// InvenSense MPU-6500 and ICM-20602: FS_SEL 0..3, AFS_SEL 0..3 (their datasheets' tables)
constexpr Step kInvenSenseGyro[] = {{250, 131}, {500, 65.5}, {1000, 32.8}, {2000, 16.4}};
constexpr Step kInvenSenseAccel[] = {{2, 16384}, {4, 8192}, {8, 4096}, {16, 2048}};
// ST LSM6DS3: 4.375, 8.75, 17.5, 35, 70 mdps/LSB; 0.061, 0.122, 0.244, 0.488 mg/LSB
constexpr Step kLsm6ds3Gyro[] = {{125, 1000 / 4.375},
                                 {245, 1000 / 8.75},
                                 {500, 1000 / 17.5},
                                 {1000, 1000 / 35.0},
                                 {2000, 1000 / 70.0}};
constexpr Step kLsm6ds3Accel[] = {
    {2, 1000 / 0.061}, {4, 1000 / 0.122}, {8, 1000 / 0.244}, {16, 1000 / 0.488}};

template <size_t N>
double Lookup(const Step (&steps)[N], double range, const std::string& part, const char* unit) {
  std::string offered;
  for (const Step& s : steps) {
    if (Near(s.range, range)) return s.lsb_per_unit;
    char text[32];
    std::snprintf(text, sizeof(text), "%s%g", offered.empty() ? "" : ", ", s.range);
    offered += text;
  }
  char given[32];
  std::snprintf(given, sizeof(given), "%g", range);
  throw InputError(part + " has no full-scale range of +-" + given + " " + unit + "; it offers +-" +
                   offered + " " + unit);
}

// the element of 3x3 matrix m (row-major) at row r, column c
double& At(double* m, int r, int c) { return m[3 * r + c]; }

}  // namespace

double GyroSensitivity(const std::string& part, double range_dps) {
  if (part == "mpu6500" || part == "icm20602")
    return Lookup(kInvenSenseGyro, range_dps, part, "dps");
  if (part == "lsm6ds3") return Lookup(kLsm6ds3Gyro, range_dps, part, "dps");
  return 32768 / range_dps;
}

double AccelSensitivity(const std::string& part, double range_g) {
  if (part == "mpu6500" || part == "icm20602") return Lookup(kInvenSenseAccel, range_g, part, "g");
  if (part == "lsm6ds3") return Lookup(kLsm6ds3Accel, range_g, part, "g");
  return 32768 / range_g;
}

ImuFigures ImuPart(const std::string& part) {
  // datasheet figures where the part's datasheet gives them; bias instability and the drift's
  // correlation time are not on these datasheets: typical consumer-MEMS figures, marked as such
  // in the README
  if (part == "icm20602") {
    return {2000, 16.4,   0.004, 1,     0.003, 100,  0.01, 0.02, 4,
            8192, 100e-6, 0.025, 50e-6, 100,   0.01, 0.02, 1000, 250};
  }
  if (part == "mpu6500") {
    return {2000, 16.4,   0.01, 5,     0.005, 100,  0.03, 0.02, 4,
            8192, 300e-6, 0.06, 80e-6, 100,   0.03, 0.02, 1000, 250};
  }
  if (part == "lsm6ds3") {
    return {2000,         1000 / 70.0, 0.007, 10,    0.003, 100,  0.01, 0.01, 4,
            1000 / 0.122, 90e-6,       0.04,  50e-6, 100,   0.01, 0.01, 1666, 400};
  }
  if (part == "custom") {
    return {2000, 32768 / 2000.0, 0,  0, 0, 100, 0, 0, 4, 32768 / 4.0, 0, 0, 0, 100, 0,
            0,    1000,           250};
  }
  throw InputError("unknown IMU part '" + part + "'");
}

double GaussMarkovAllanPeak() {
  // Allan variance of a first-order Gauss-Markov process of unit variance at tau = x T
  // (IEEE Std 952, annex C): (2 / x) (1 - (3 - 4 e^-x + e^-2x) / (2 x))
  auto variance = [](double x) {
    return 2 / x * (1 - (3 - 4 * std::exp(-x) + std::exp(-2 * x)) / (2 * x));
  };
  double lo = 0.5, hi = 5;
  for (int i = 0; i < 100; ++i) {
    const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    (variance(a) < variance(b) ? lo : hi) = variance(a) < variance(b) ? a : b;
  }
  return std::sqrt(variance((lo + hi) / 2));
}

Imu::Imu(Params params) : p_(std::move(params)), f_(ImuPart(p_.part)) {
  // a named part supplies what the robot file leaves out; a range given without its sensitivity
  // takes the part's sensitivity at that range
  auto take = [&](const char* name, double value, double& figure) {
    if (param::Given(p_.given, name)) figure = value;
  };
  take("gyro_range_dps", p_.gyro_range_dps, f_.gyro_range_dps);
  f_.gyro_sensitivity_lsb_per_dps = GyroSensitivity(p_.part, f_.gyro_range_dps);
  take("gyro_sensitivity_lsb_per_dps", p_.gyro_sensitivity_lsb_per_dps,
       f_.gyro_sensitivity_lsb_per_dps);
  take("gyro_noise_dps_per_rt_hz", p_.gyro_noise_dps_per_rt_hz, f_.gyro_noise_dps_per_rt_hz);
  take("gyro_bias_dps", p_.gyro_bias_dps, f_.gyro_bias_dps);
  take("gyro_bias_instability_dps", p_.gyro_bias_instability_dps, f_.gyro_bias_instability_dps);
  take("gyro_bias_tau_s", p_.gyro_bias_tau_s, f_.gyro_bias_tau_s);
  take("gyro_scale_error", p_.gyro_scale_error, f_.gyro_scale_error);
  take("gyro_cross_axis", p_.gyro_cross_axis, f_.gyro_cross_axis);
  take("accel_range_g", p_.accel_range_g, f_.accel_range_g);
  f_.accel_sensitivity_lsb_per_g = AccelSensitivity(p_.part, f_.accel_range_g);
  take("accel_sensitivity_lsb_per_g", p_.accel_sensitivity_lsb_per_g,
       f_.accel_sensitivity_lsb_per_g);
  take("accel_noise_g_per_rt_hz", p_.accel_noise_g_per_rt_hz, f_.accel_noise_g_per_rt_hz);
  take("accel_bias_g", p_.accel_bias_g, f_.accel_bias_g);
  take("accel_bias_instability_g", p_.accel_bias_instability_g, f_.accel_bias_instability_g);
  take("accel_bias_tau_s", p_.accel_bias_tau_s, f_.accel_bias_tau_s);
  take("accel_scale_error", p_.accel_scale_error, f_.accel_scale_error);
  take("accel_cross_axis", p_.accel_cross_axis, f_.accel_cross_axis);
  take("odr_hz", p_.odr_hz, f_.odr_hz);
  take("dlpf_hz", p_.dlpf_hz, f_.dlpf_hz);
}

void Imu::Bind(BindContext& ctx) {
  site_ = ctx.SiteId(p_.site);
  dt_s_ = ctx.period_s();
  // the output cannot change more often than the component runs
  sample_period_s_ = std::max(1 / f_.odr_hz, dt_s_);
  dlpf_alpha_ = 1 - std::exp(-2 * std::numbers::pi * f_.dlpf_hz * dt_s_);
  truth_ = !p_.truth_out.empty();
  const std::string out = p_.out.empty() ? ctx.name() : p_.out;
  const double peak = GaussMarkovAllanPeak();

  // white noise of density N sampled every dt has a standard deviation of N / sqrt(dt)
  gyro_.range = f_.gyro_range_dps * kRadPerDeg;
  gyro_.counts_per_unit = f_.gyro_sensitivity_lsb_per_dps / kRadPerDeg;
  gyro_.noise_sd = f_.gyro_noise_dps_per_rt_hz * kRadPerDeg / std::sqrt(dt_s_);
  gyro_.bias = f_.gyro_bias_dps * kRadPerDeg;
  gyro_.drift_sd = f_.gyro_bias_instability_dps * kRadPerDeg / peak;
  gyro_.drift_decay = std::exp(-dt_s_ / f_.gyro_bias_tau_s);
  gyro_.drift_step_sd = gyro_.drift_sd * std::sqrt(1 - gyro_.drift_decay * gyro_.drift_decay);
  gyro_.scale_error = f_.gyro_scale_error;
  gyro_.cross_axis = f_.gyro_cross_axis;
  accel_.range = f_.accel_range_g * kStandardGravity_m_s2;
  accel_.counts_per_unit = f_.accel_sensitivity_lsb_per_g / kStandardGravity_m_s2;
  accel_.noise_sd = f_.accel_noise_g_per_rt_hz * kStandardGravity_m_s2 / std::sqrt(dt_s_);
  accel_.bias = f_.accel_bias_g * kStandardGravity_m_s2;
  accel_.drift_sd = f_.accel_bias_instability_g * kStandardGravity_m_s2 / peak;
  accel_.drift_decay = std::exp(-dt_s_ / f_.accel_bias_tau_s);
  accel_.drift_step_sd = accel_.drift_sd * std::sqrt(1 - accel_.drift_decay * accel_.drift_decay);
  accel_.scale_error = f_.accel_scale_error;
  accel_.cross_axis = f_.accel_cross_axis;

  for (int i = 0; i < 3; ++i) {
    const std::string g = std::string(".gyro_") + kAxes[i];
    const std::string a = std::string(".accel_") + kAxes[i];
    gyro_.si[i] = ctx.WriteSignal(out + g + "_rad_s");
    gyro_.counts[i] = ctx.WriteSignal(out + g + "_counts");
    accel_.si[i] = ctx.WriteSignal(out + a + "_m_s2");
    accel_.counts[i] = ctx.WriteSignal(out + a + "_counts");
    if (truth_) {
      const std::string& t = p_.truth_out;
      gyro_.truth[i] = ctx.WriteSignal(t + g + "_rad_s");
      gyro_.truth_scale[i] = ctx.WriteSignal(t + ".gyro_scale_error_" + kAxes[i]);
      gyro_.truth_bias[i] = ctx.WriteSignal(t + ".gyro_bias_" + kAxes[i] + "_rad_s");
      accel_.truth[i] = ctx.WriteSignal(t + a + "_m_s2");
      accel_.truth_scale[i] = ctx.WriteSignal(t + ".accel_scale_error_" + kAxes[i]);
      accel_.truth_bias[i] = ctx.WriteSignal(t + ".accel_bias_" + kAxes[i] + "_m_s2");
    }
  }
  const std::string name = ctx.name();
  gyro_.draws = ctx.Rng(name + ".gyro.errors");
  gyro_.noise = ctx.Rng(name + ".gyro.noise");
  gyro_.drift = ctx.Rng(name + ".gyro.drift");
  accel_.draws = ctx.Rng(name + ".accel.errors");
  accel_.noise = ctx.Rng(name + ".accel.noise");
  accel_.drift = ctx.Rng(name + ".accel.drift");
  ctx.SetStateSize(kStateSize);
}

void Imu::DrawErrors(const ResetContext& ctx, const Channel& c, double* slots) const {
  // every tolerance is a +- bound: drawn uniformly inside it, in a fixed order
  auto within = [&](double tolerance) { return tolerance * (2 * ctx.Uniform(c.draws) - 1); };
  double* m = slots + kMatrix;
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) {
      At(m, r, col) = r == col ? 1 + within(c.scale_error) : within(c.cross_axis);
    }
  }
  for (int i = 0; i < 3; ++i) slots[kTurnOn + i] = within(c.bias);
  // the drift starts in its stationary distribution
  for (int i = 0; i < 3; ++i) slots[kDrift + i] = c.drift_sd * ctx.Normal(c.drift);
  // a calibrated z gyro replaces its draws after they are made, so that the other axes and the
  // later draws stay those of the same seed
  if (&c == &gyro_) {
    if (param::Given(p_.given, "gyro_z_scale_error")) At(m, 2, 2) = 1 + p_.gyro_z_scale_error;
    if (param::Given(p_.given, "gyro_z_bias_dps")) {
      slots[kTurnOn + 2] = p_.gyro_z_bias_dps * kRadPerDeg;
    }
  }
}

void Imu::SiteMotion(const mjModel& m, const mjData& d, const double* previous_v,
                     double out_omega[3], double out_force[3], double out_v[3]) const {
  // the motion of the material point at the site, world axes: its velocity differenced over one
  // period is the point's acceleration, lever-arm terms included; the chip feels it minus
  // gravity
  double v6[6];
  mj_objectVelocity(&m, &d, mjOBJ_SITE, site_, v6, 0);
  double f_world[3];
  for (int i = 0; i < 3; ++i) {
    out_v[i] = v6[3 + i];
    const double a = previous_v == nullptr ? 0 : (out_v[i] - previous_v[i]) / dt_s_;
    f_world[i] = a - m.opt.gravity[i];
  }
  // site_xmat is row-major with the site's axes as columns: the transpose rotates into it
  const double* r = d.site_xmat + 9 * site_;
  for (int i = 0; i < 3; ++i) {
    out_omega[i] = r[i] * v6[0] + r[3 + i] * v6[1] + r[6 + i] * v6[2];
    out_force[i] = r[i] * f_world[0] + r[3 + i] * f_world[1] + r[6 + i] * f_world[2];
  }
}

void Imu::Update(const SenseContext& ctx, const Channel& c, const double truth[3], double* slots,
                 bool sample) const {
  const double* m = slots + kMatrix;
  for (int i = 0; i < 3; ++i) {
    if (c.drift_sd > 0) {
      slots[kDrift + i] = c.drift_decay * slots[kDrift + i] + c.drift_step_sd * ctx.Normal(c.drift);
    }
  }
  for (int i = 0; i < 3; ++i) {
    double y = slots[kTurnOn + i] + slots[kDrift + i];
    for (int j = 0; j < 3; ++j) y += m[3 * i + j] * truth[j];
    if (c.noise_sd > 0) y += c.noise_sd * ctx.Normal(c.noise);
    slots[kFilter + i] += dlpf_alpha_ * (y - slots[kFilter + i]);
  }
  if (truth_) {
    for (int i = 0; i < 3; ++i) {
      ctx.Write(c.truth[i], truth[i]);
      ctx.Write(c.truth_bias[i], slots[kTurnOn + i] + slots[kDrift + i]);
    }
  }
  if (!sample) return;
  // the registers: saturated at full scale, quantised to the sensitivity, 16-bit two's complement
  for (int i = 0; i < 3; ++i) {
    const double held = std::clamp(slots[kFilter + i], -c.range, c.range);
    const double counts = std::clamp(std::round(held * c.counts_per_unit), -32768.0, 32767.0);
    ctx.Write(c.counts[i], counts);
    ctx.Write(c.si[i], counts / c.counts_per_unit);
  }
}

void Imu::Reset(const ResetContext& ctx) const {
  std::span<double> s = ctx.state();
  DrawErrors(ctx, gyro_, s.data() + kGyro);
  DrawErrors(ctx, accel_, s.data() + kAccel);
  double omega[3], force[3];
  SiteMotion(ctx.model(), ctx.data(), nullptr, omega, force, s.data() + kPreviousV);

  // the filters start settled on what the chip would read now, without noise
  for (const auto& [c, slots, truth] :
       {std::tuple{&gyro_, s.data() + kGyro, static_cast<const double*>(omega)},
        std::tuple{&accel_, s.data() + kAccel, static_cast<const double*>(force)}}) {
    for (int i = 0; i < 3; ++i) {
      double y = slots[kTurnOn + i] + slots[kDrift + i];
      for (int j = 0; j < 3; ++j) y += slots[kMatrix + 3 * i + j] * truth[j];
      slots[kFilter + i] = y;
      const double held = std::clamp(y, -c->range, c->range);
      const double counts = std::clamp(std::round(held * c->counts_per_unit), -32768.0, 32767.0);
      ctx.Write(c->counts[i], counts);
      ctx.Write(c->si[i], counts / c->counts_per_unit);
      if (truth_) {
        ctx.Write(c->truth[i], truth[i]);
        ctx.Write(c->truth_scale[i], slots[kMatrix + 4 * i] - 1);
        ctx.Write(c->truth_bias[i], slots[kTurnOn + i] + slots[kDrift + i]);
      }
    }
  }
  s[kNextSample] = ctx.time_s() + sample_period_s_;
}

void Imu::Sense(const SenseContext& ctx) const {
  std::span<double> s = ctx.state();
  double omega[3], force[3], v[3];
  SiteMotion(ctx.model(), ctx.data(), s.data() + kPreviousV, omega, force, v);
  std::copy(v, v + 3, s.data() + kPreviousV);

  // the registers change at the output data rate; half a step absorbs rounding of the times
  const bool sample = ctx.time_s() + 0.5 * dt_s_ >= s[kNextSample];
  if (sample) s[kNextSample] += sample_period_s_;
  Update(ctx, gyro_, omega, s.data() + kGyro, sample);
  Update(ctx, accel_, force, s.data() + kAccel, sample);
}

}  // namespace unimouse::plugins
