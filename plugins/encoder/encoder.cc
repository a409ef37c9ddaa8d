// SPDX-License-Identifier: GPL-3.0-or-later
#include "encoder.h"

#include <numbers>

namespace unimouse::plugins {
namespace {

// state slots
constexpr int kAccumulated = 0;  // theta_acc of algorithm 1, motor shaft radians
constexpr int kLastWheel = 1;    // wheel hinge angle at the previous period
constexpr int kLastJitter = 2;   // edge offset applied at the previous period, radians

}  // namespace

Encoder::Encoder(Params params)
    : p_(std::move(params)),
      count_angle_rad_(2 * std::numbers::pi / (p_.cpr * (p_.quadrature_x4 ? 4 : 1))) {}

void Encoder::Bind(BindContext& ctx) {
  const int joint = ctx.JointId(p_.joint);
  UNIMOUSE_THROW_UNLESS(ctx.model().jnt_type[joint] == mjJNT_HINGE,
                        "joint '" + p_.joint + "' is not a hinge");
  qpos_ = ctx.model().jnt_qposadr[joint];
  counts_ = ctx.WriteSignal(p_.counts_out);
  if (p_.jitter_counts_sd > 0) jitter_ = ctx.Rng(ctx.name());
  ctx.SetStateSize(3);
}

void Encoder::Reset(const ResetContext& ctx) const {
  ctx.state()[kAccumulated] = 0;
  ctx.state()[kLastWheel] = ctx.data().qpos[qpos_];
  ctx.state()[kLastJitter] = 0;
  ctx.Write(counts_, 0);
}

void Encoder::Sense(const SenseContext& ctx) const {
  std::span<double> s = ctx.state();
  const double wheel_rad = ctx.data().qpos[qpos_];
  double delta_rad = p_.gear_ratio * (wheel_rad - s[kLastWheel]);
  s[kLastWheel] = wheel_rad;

  // moving every edge by a fresh offset adds the difference of two offsets: no drift
  if (jitter_.index >= 0) {
    const double offset = p_.jitter_counts_sd * count_angle_rad_ * ctx.Normal(jitter_);
    delta_rad += offset - s[kLastJitter];
    s[kLastJitter] = offset;
  }

  // algorithm 1
  int counts = 0;
  double acc = s[kAccumulated] + delta_rad;
  while (acc >= count_angle_rad_) {
    ++counts;
    acc -= count_angle_rad_;
  }
  while (acc <= -count_angle_rad_) {
    --counts;
    acc += count_angle_rad_;
  }
  s[kAccumulated] = acc;
  ctx.Write(counts_, counts);
}

}  // namespace unimouse::plugins
